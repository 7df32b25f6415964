/*
 * rotor.c: a rigid rotor carried by two raceway bearings through the C ABI.
 *
 * The rotor (4 degrees of freedom: centre x, y and tilts tx about x, ty about y) has a
 * static unbalance U = m_u e at its centre of mass, gravity along -y, gyroscopic coupling
 * (polar inertia Ip at speed Omega) and a viscous pedestal damper c at each bearing
 * station. Bearing A sits at z = -a and bearing B at z = span - a from the centre of mass
 * (a = com * span). A point of the shaft at z moves by x + z ty, y - z tx.
 *
 * Equations of motion (rigid rotor with gyroscopic moments: Genta, "Dynamics of Rotating
 * Systems", 2005, ch. 4; Childs, "Turbomachinery Rotordynamics", 1993, ch. 1):
 *   m x''  = sum Fx + U Omega^2 cos(Omega t)
 *   m y''  = sum Fy + U Omega^2 sin(Omega t) - m g
 *   It tx'' + Ip Omega ty' = sum (Mx - z Fy)
 *   It ty'' - Ip Omega tx' = sum (My + z Fx)
 *
 * Coupling, at a fixed macro step H = (2 pi / Omega) / steps_per_rev: at t_n the rotor
 * gives each bearing its motion (x, y, z = 0, tilts, their rates, Omega) and the bearing
 * steps to t_n + H. The scene must use inputs.rule = "hold", so the outputs F0, K, C
 * belong to the motion q0, v0 given at t_n. Over [t_n, t_n + H] the rotor integrates with
 * the bearing force linearised about that point,
 *   F(q, v) = F0 - K (q - q0) - C (v - v0)     (q = x, y, rx, ry of the bearing),
 * with the classical fourth-order Runge-Kutta method (Hairer, Norsett & Wanner, "Solving
 * Ordinary Differential Equations I", 1993, II.1), `substeps` steps per macro step.
 * The coupling error is second order in H for a nonlinear bearing (the linearisation
 * error is O(|q - q0|^2)) and zero for a linear one. With coupling=hold the rotor uses F0
 * alone over the step (the plain explicit zero-order-hold co-simulation, first order in
 * H, and stable only while the bearing stiffness times H stays below the damping:
 * Kuebler & Schiehlen, "Two methods of simulator coupling", 2000).
 *
 * The orbit is analysed over the last `avg_revs` revolutions (an integer number of macro
 * steps): the mean and the amplitude of the first harmonic (the discrete Fourier
 * coefficient at Omega, exact for a sampled sinusoid) of each bearing's x and y.
 *
 * Usage: rotor [key=value ...]; keys below (SI units, speed in rpm). Output: `key value`
 * lines; with csv=<path>, also the macro-step history as CSV.
 */
#include "raceway.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* The bearing used when no scene=<path> is given (the same as examples/c/bearing.toml). */
static const char *DEFAULT_SCENE =
    "title = \"rotor.c bearing: 6205, quasi-static, inputs held over a step\"\n"
    "bearing = \"6205\"\n"
    "[model]\n"
    "level = \"quasi_static\"\n"
    "causality = \"motion\"\n"
    "[inputs]\n"
    "rule = \"hold\"\n";

typedef struct {
  double mass, span, com, it, ip, speed_rpm, unbalance, gravity, damping;
  int steps_per_rev, substeps, revs, avg_revs;
  int hold; /* coupling=hold: the bearing force F0 held over the step (first order) */
  const char *scene_path, *csv_path;
} Params;

/* Generalised coordinates of a bearing (x, y, rx, ry) and their matrix entries. */
enum { NQ = 4 };
static const char *QNAME[NQ] = {"x", "y", "rx", "ry"};

typedef struct {
  RacewayComponent *c;
  double z;                       /* axial position from the centre of mass, m */
  double q0[NQ], v0[NQ], f0[NQ];  /* linearisation point and generalised force there */
  double k[NQ][NQ], cm[NQ][NQ];   /* stiffness and damping, -dF_i/dq_j, -dF_i/dv_j */
  uint32_t vr_k[NQ * NQ], vr_c[NQ * NQ];
} Bearing;

/* Rotor state: x, y, tx, ty, then their rates. */
enum { NS = 8 };

static void die(const char *what, RacewayComponent *c) {
  fprintf(stderr, "rotor: %s failed: %s\n", what, c ? raceway_last_error(c) : "");
  exit(1);
}

#define CHECK(call, c)                      \
  do {                                      \
    if ((call) != RACEWAY_STATUS_OK) die(#call, c); \
  } while (0)

static char *read_file(const char *path) {
  FILE *f = fopen(path, "rb");
  long n;
  char *s;
  if (!f) {
    fprintf(stderr, "rotor: cannot open %s\n", path);
    exit(1);
  }
  fseek(f, 0, SEEK_END);
  n = ftell(f);
  fseek(f, 0, SEEK_SET);
  s = malloc((size_t)n + 1);
  if (!s || fread(s, 1, (size_t)n, f) != (size_t)n) {
    fprintf(stderr, "rotor: cannot read %s\n", path);
    exit(1);
  }
  s[n] = '\0';
  fclose(f);
  return s;
}

/* Motion of the shaft at a bearing station z (generalised coordinates of the bearing). */
static void station(const double *s, double z, double q[NQ], double v[NQ]) {
  q[0] = s[0] + z * s[3];
  q[1] = s[1] - z * s[2];
  q[2] = s[2];
  q[3] = s[3];
  v[0] = s[4] + z * s[7];
  v[1] = s[5] - z * s[6];
  v[2] = s[6];
  v[3] = s[7];
}

/* Right-hand side of the rotor at time t (bearing forces linearised, see the top). */
static void rhs(const Params *p, const Bearing *b, double t, const double *s, double *ds) {
  double omega = p->speed_rpm * PI / 30.0;
  double fx = p->unbalance * omega * omega * cos(omega * t);
  double fy = p->unbalance * omega * omega * sin(omega * t) - p->mass * p->gravity;
  double mx = -p->ip * omega * s[7];
  double my = p->ip * omega * s[6];
  int i, j, n;
  for (n = 0; n < 2; n++) {
    double q[NQ], v[NQ], f[NQ];
    station(s, b[n].z, q, v);
    for (i = 0; i < NQ; i++) {
      f[i] = b[n].f0[i];
      for (j = 0; j < NQ && !p->hold; j++)
        f[i] -= b[n].k[i][j] * (q[j] - b[n].q0[j]) + b[n].cm[i][j] * (v[j] - b[n].v0[j]);
    }
    f[0] -= p->damping * v[0];
    f[1] -= p->damping * v[1];
    fx += f[0];
    fy += f[1];
    mx += f[2] - b[n].z * f[1];
    my += f[3] + b[n].z * f[0];
  }
  for (i = 0; i < 4; i++) ds[i] = s[4 + i];
  ds[4] = fx / p->mass;
  ds[5] = fy / p->mass;
  ds[6] = mx / p->it;
  ds[7] = my / p->it;
}

static void rk4(const Params *p, const Bearing *b, double t, double h, double *s) {
  double k1[NS], k2[NS], k3[NS], k4[NS], tmp[NS];
  int i;
  rhs(p, b, t, s, k1);
  for (i = 0; i < NS; i++) tmp[i] = s[i] + 0.5 * h * k1[i];
  rhs(p, b, t + 0.5 * h, tmp, k2);
  for (i = 0; i < NS; i++) tmp[i] = s[i] + 0.5 * h * k2[i];
  rhs(p, b, t + 0.5 * h, tmp, k3);
  for (i = 0; i < NS; i++) tmp[i] = s[i] + h * k3[i];
  rhs(p, b, t + h, tmp, k4);
  for (i = 0; i < NS; i++) s[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

static uint32_t lookup(const char *name) {
  uint32_t vr = 0;
  if (raceway_variable_vr(name, &vr) != RACEWAY_STATUS_OK) {
    fprintf(stderr, "rotor: no variable %s\n", name);
    exit(1);
  }
  return vr;
}

/* Give the bearing the shaft motion at t, step it to t + h, read F0, K, C. */
static void couple(Bearing *b, const double *s, double omega, double t, double h) {
  static const uint32_t in[11] = {
      RACEWAY_VR_SHAFT_X,  RACEWAY_VR_SHAFT_Y,  RACEWAY_VR_SHAFT_Z,  RACEWAY_VR_SHAFT_RX,
      RACEWAY_VR_SHAFT_RY, RACEWAY_VR_SHAFT_VX, RACEWAY_VR_SHAFT_VY, RACEWAY_VR_SHAFT_VZ,
      RACEWAY_VR_SHAFT_WX, RACEWAY_VR_SHAFT_WY, RACEWAY_VR_SHAFT_OMEGA};
  static const uint32_t out[NQ] = {RACEWAY_VR_FORCE_X, RACEWAY_VR_FORCE_Y,
                                   RACEWAY_VR_MOMENT_X, RACEWAY_VR_MOMENT_Y};
  double val[11], kk[NQ * NQ], cc[NQ * NQ];
  int i, j;
  station(s, b->z, b->q0, b->v0);
  val[0] = b->q0[0];
  val[1] = b->q0[1];
  val[2] = 0.0;
  val[3] = b->q0[2];
  val[4] = b->q0[3];
  val[5] = b->v0[0];
  val[6] = b->v0[1];
  val[7] = 0.0;
  val[8] = b->v0[2];
  val[9] = b->v0[3];
  val[10] = omega;
  CHECK(raceway_set_reals(b->c, in, val, 11), b->c);
  CHECK(raceway_do_step(b->c, t, h), b->c);
  CHECK(raceway_get_reals(b->c, out, b->f0, NQ), b->c);
  CHECK(raceway_get_reals(b->c, b->vr_k, kk, NQ * NQ), b->c);
  CHECK(raceway_get_reals(b->c, b->vr_c, cc, NQ * NQ), b->c);
  for (i = 0; i < NQ; i++)
    for (j = 0; j < NQ; j++) {
      b->k[i][j] = kk[NQ * i + j];
      b->cm[i][j] = cc[NQ * i + j];
    }
}

static int parse(Params *p, const char *arg) {
  const char *eq = strchr(arg, '=');
  const char *v;
  size_t n;
  if (!eq) return 0;
  n = (size_t)(eq - arg);
  v = eq + 1;
#define REAL(key, field) \
  if (strlen(key) == n && strncmp(arg, key, n) == 0) return (p->field = atof(v)), 1;
#define INT(key, field) \
  if (strlen(key) == n && strncmp(arg, key, n) == 0) return (p->field = atoi(v)), 1;
  REAL("mass", mass)
  REAL("span", span)
  REAL("com", com)
  REAL("it", it)
  REAL("ip", ip)
  REAL("speed_rpm", speed_rpm)
  REAL("unbalance", unbalance)
  REAL("gravity", gravity)
  REAL("damping", damping)
  INT("steps_per_rev", steps_per_rev)
  INT("substeps", substeps)
  INT("revs", revs)
  INT("avg_revs", avg_revs)
  if (n == 5 && strncmp(arg, "scene", 5) == 0) return (p->scene_path = v), 1;
  if (n == 3 && strncmp(arg, "csv", 3) == 0) return (p->csv_path = v), 1;
  if (n == 8 && strncmp(arg, "coupling", 8) == 0) {
    if (strcmp(v, "linear") == 0) return (p->hold = 0), 1;
    if (strcmp(v, "hold") == 0) return (p->hold = 1), 1;
  }
  return 0;
}

int main(int argc, char **argv) {
  Params p;
  Bearing b[2];
  double s[NS] = {0};
  double omega, period, h, t = 0.0;
  double sum[2][2], cosum[2][2], sinsum[2][2], fsum[2][2];
  char *scene;
  char err[1024];
  char name[32];
  int i, j, n, step, nsteps, navg;
  FILE *csv = NULL;

  /* Defaults: a 5 kg rotor, 0.2 m span, 25 mm journal (solid cylinder inertias). */
  p.mass = 5.0;
  p.span = 0.2;
  p.com = 0.5;
  p.it = -1.0;
  p.ip = -1.0;
  p.speed_rpm = 10000.0;
  p.unbalance = 1.2e-5; /* kg m: ISO 1940 grade G2.5 at 10000 rpm for 5 kg */
  p.gravity = 9.81;
  p.damping = 2000.0;
  p.steps_per_rev = 64;
  p.substeps = 2;
  p.revs = 40;
  p.avg_revs = 10;
  p.scene_path = NULL;
  p.csv_path = NULL;
  p.hold = 0;
  for (i = 1; i < argc; i++)
    if (!parse(&p, argv[i])) {
      fprintf(stderr, "rotor: unknown argument %s\n", argv[i]);
      return 2;
    }
  if (p.it < 0.0) p.it = p.mass * (3.0 * 0.0125 * 0.0125 + p.span * p.span) / 12.0;
  if (p.ip < 0.0) p.ip = 0.5 * p.mass * 0.0125 * 0.0125;
  if (!(p.mass > 0.0 && p.span > 0.0 && p.com > 0.0 && p.com < 1.0 && p.it > 0.0 &&
        p.speed_rpm > 0.0 && p.steps_per_rev >= 4 && p.substeps >= 1 &&
        p.avg_revs >= 1 && p.revs > p.avg_revs)) {
    fprintf(stderr, "rotor: parameters out of range\n");
    return 2;
  }

  scene = p.scene_path ? read_file(p.scene_path) : NULL;
  for (n = 0; n < 2; n++) {
    b[n].c = raceway_create(scene ? scene : DEFAULT_SCENE, err, sizeof err);
    if (!b[n].c) {
      fprintf(stderr, "rotor: bearing refused: %s\n", err);
      return 1;
    }
    for (i = 0; i < NQ; i++)
      for (j = 0; j < NQ; j++) {
        snprintf(name, sizeof name, "K.%s.%s", QNAME[i], QNAME[j]);
        b[n].vr_k[NQ * i + j] = lookup(name);
        snprintf(name, sizeof name, "C.%s.%s", QNAME[i], QNAME[j]);
        b[n].vr_c[NQ * i + j] = lookup(name);
      }
  }
  b[0].z = -p.com * p.span;
  b[1].z = (1.0 - p.com) * p.span;

  omega = p.speed_rpm * PI / 30.0;
  period = 2.0 * PI / omega;
  h = period / p.steps_per_rev;
  nsteps = p.revs * p.steps_per_rev;
  navg = p.avg_revs * p.steps_per_rev;
  memset(sum, 0, sizeof sum);
  memset(cosum, 0, sizeof cosum);
  memset(sinsum, 0, sizeof sinsum);
  memset(fsum, 0, sizeof fsum);
  if (p.csv_path) {
    csv = fopen(p.csv_path, "w");
    if (!csv) {
      fprintf(stderr, "rotor: cannot write %s\n", p.csv_path);
      return 1;
    }
    fprintf(csv, "t,xA,yA,xB,yB,FxA,FyA,FxB,FyB\n");
  }

  for (step = 0; step < nsteps; step++) {
    for (n = 0; n < 2; n++) couple(&b[n], s, omega, t, h);
    for (i = 0; i < p.substeps; i++) rk4(&p, b, t + i * (h / p.substeps), h / p.substeps, s);
    /* The time of the macro point, as the bearings count it. */
    CHECK(raceway_get_time(b[0].c, &t), b[0].c);
    if (csv) {
      double qa[NQ], qb[NQ], v[NQ];
      station(s, b[0].z, qa, v);
      station(s, b[1].z, qb, v);
      fprintf(csv, "%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e\n", t, qa[0], qa[1], qb[0],
              qb[1], b[0].f0[0], b[0].f0[1], b[1].f0[0], b[1].f0[1]);
    }
    if (step >= nsteps - navg) {
      /* Phase from the step count (exact multiples of 2 pi / steps_per_rev). */
      double phase = 2.0 * PI * (double)((step + 1) % p.steps_per_rev) / p.steps_per_rev;
      for (n = 0; n < 2; n++) {
        double q[NQ], v[NQ];
        station(s, b[n].z, q, v);
        for (i = 0; i < 2; i++) {
          sum[n][i] += q[i];
          cosum[n][i] += q[i] * cos(phase);
          sinsum[n][i] += q[i] * sin(phase);
          fsum[n][i] += b[n].f0[i];
        }
      }
    }
  }
  if (csv) fclose(csv);

  printf("macro_step %.12e\n", h);
  printf("macro_steps %d\n", nsteps);
  printf("t_end %.12e\n", t);
  for (n = 0; n < 2; n++)
    for (i = 0; i < 2; i++) {
      const char *ab = n == 0 ? "A" : "B";
      const char *xy = i == 0 ? "x" : "y";
      double a = 2.0 * cosum[n][i] / navg, c = 2.0 * sinsum[n][i] / navg;
      printf("bearing.%s.%s.mean %.12e\n", ab, xy, sum[n][i] / navg);
      printf("bearing.%s.%s.amplitude %.12e\n", ab, xy, sqrt(a * a + c * c));
      printf("bearing.%s.force.%s.mean %.12e\n", ab, xy, fsum[n][i] / navg);
    }
  for (n = 0; n < 2; n++) raceway_free(b[n].c);
  free(scene);
  return 0;
}

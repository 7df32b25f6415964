// stiffness.cpp: a bearing's radial load-deflection curve and stiffness, from C++ through
// the C ABI (include/raceway.h).
//
// The inner ring is held at a radial displacement y (x = 0, no tilt) spinning at
// `speed_rpm`; for each y of a sweep the bearing steps once and gives the force F_y and
// the stiffness K_yy = -dF_y/dy. Beside it the program measures the same derivative by a
// central difference of the force: from a saved state it steps at y + dy and at y - dy
// (restoring the state between, so both see the same time and ball positions) and prints
// -(F(y + dy) - F(y - dy)) / (2 dy), which must agree with K_yy.
//
// Shows C++ use of the C ABI: std::unique_ptr owners for instances and saved states (so
// nothing leaks when an exception is thrown), every refused call turned into an exception
// carrying raceway_last_error, and a check that the header matches the library loaded.
//
// Usage: stiffness SCENE [speed_rpm=10000] [max_um=20] [points=8]
//   SCENE: a motion-driven scene with inputs.rule = "hold" (e.g. examples/c/bearing.toml).
// Output: `version V`, then one line per point: y_um F_y_N K_yy_N_per_m K_fd_N_per_m.
#include "raceway.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

struct ComponentFree {
  void operator()(RacewayComponent *c) const { raceway_free(c); }
};
struct StateFree {
  void operator()(RacewayState *s) const { raceway_state_free(s); }
};
using State = std::unique_ptr<RacewayState, StateFree>;

// One bearing instance; every refused call throws with the instance's message.
class Bearing {
 public:
  explicit Bearing(const std::string &scene) {
    char error[1024] = "";
    c_.reset(raceway_create(scene.c_str(), error, sizeof error));
    if (!c_) throw std::runtime_error(std::string("scene refused: ") + error);
  }

  void set(uint32_t vr, double value) { check(raceway_set_real(c_.get(), vr, value), "set"); }

  double get(uint32_t vr) const {
    double value = 0.0;
    check(raceway_get_real(c_.get(), vr, &value), "get");
    return value;
  }

  // Advance by h from the instance's current time.
  void step(double h) {
    double t = 0.0;
    check(raceway_get_time(c_.get(), &t), "get_time");
    check(raceway_do_step(c_.get(), t, h), "do_step");
  }

  State save() const {
    RacewayState *s = nullptr;
    check(raceway_state_get(c_.get(), &s), "state_get");
    return State(s);
  }

  void restore(const State &s) { check(raceway_state_set(c_.get(), s.get()), "state_set"); }

 private:
  void check(RacewayStatus status, const char *what) const {
    if (status != RACEWAY_STATUS_OK)
      throw std::runtime_error(std::string(what) + ": " + raceway_last_error(c_.get()));
  }

  std::unique_ptr<RacewayComponent, ComponentFree> c_;
};

std::string read_file(const char *path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(std::string("cannot open ") + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

double arg(int argc, char **argv, int i, double fallback) {
  return argc > i ? std::atof(argv[i]) : fallback;
}

}  // namespace

int main(int argc, char **argv) {
  // The header this program was compiled with must describe the library it runs with.
  if (std::string(raceway_version()) != RACEWAY_VERSION_STRING) {
    std::fprintf(stderr, "stiffness: header %s, library %s\n", RACEWAY_VERSION_STRING,
                 raceway_version());
    return 1;
  }
  if (argc < 2) {
    std::fprintf(stderr, "usage: stiffness SCENE [speed_rpm] [max_um] [points]\n");
    return 2;
  }
  const double pi = 3.14159265358979323846;
  const double omega = arg(argc, argv, 2, 10000.0) * pi / 30.0;
  const double y_max = arg(argc, argv, 3, 20.0) * 1e-6;
  const int points = static_cast<int>(arg(argc, argv, 4, 8.0));
  const double h = 1e-4;  // s, one step per point
  if (!(omega > 0.0 && y_max > 0.0 && points >= 2)) {
    std::fprintf(stderr, "stiffness: speed_rpm, max_um must be > 0 and points >= 2\n");
    return 2;
  }

  try {
    Bearing b(read_file(argv[1]));
    const uint32_t inputs[] = {
        RACEWAY_VR_SHAFT_X,  RACEWAY_VR_SHAFT_Y,  RACEWAY_VR_SHAFT_Z,  RACEWAY_VR_SHAFT_RX,
        RACEWAY_VR_SHAFT_RY, RACEWAY_VR_SHAFT_VX, RACEWAY_VR_SHAFT_VY, RACEWAY_VR_SHAFT_VZ,
        RACEWAY_VR_SHAFT_WX, RACEWAY_VR_SHAFT_WY};
    for (uint32_t vr : inputs) b.set(vr, 0.0);
    b.set(RACEWAY_VR_SHAFT_OMEGA, omega);

    // Force at displacement y (ring pushed towards -y: the balls push back, F_y > 0).
    auto force_at = [&](double y) {
      b.set(RACEWAY_VR_SHAFT_Y, -y);
      b.step(h);
      return b.get(RACEWAY_VR_FORCE_Y);
    };

    std::printf("version %s\n", raceway_version());
    for (int i = 1; i <= points; i++) {
      const double y = y_max * i / points;
      const double dy = 1e-4 * y;
      State before = b.save();
      const double f_plus = force_at(y + dy);
      b.restore(before);
      const double f_minus = force_at(y - dy);
      b.restore(before);
      const double f = force_at(y);
      // K is -dF/d(shaft.y); the sweep pushes along -y, so d/dy = -d/d(shaft.y).
      const double k = b.get(RACEWAY_VR_K_Y_Y);
      const double k_fd = (f_plus - f_minus) / (2.0 * dy);
      std::printf("%.6f %.9e %.9e %.9e\n", y * 1e6, f, k, k_fd);
    }
  } catch (const std::exception &e) {
    std::fprintf(stderr, "stiffness: %s\n", e.what());
    return 1;
  }
  return 0;
}

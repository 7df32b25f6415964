//! Randomised misuse, bounded in time: mutated scenes through the parser and the
//! component, and random C ABI call sequences (made-up, freed and doubly freed handles,
//! wrong lengths, NaN and huge values, state bytes truncated or flipped).
//!
//! Properties checked on every case: no panic (in Rust or behind the C ABI, where it
//! would show as `RACEWAY_STATUS_PANIC`), no NaN or infinity read from an instance after
//! a successful call, every refusal leaves a non-empty message, a refused call leaves the
//! instance's time and outputs as they were, and no case takes longer than
//! `HANG_SECONDS` of thread CPU time (reported as a hang).
//!
//! Each test runs for `RACEWAY_FUZZ_SECONDS` (default 25; the two tests make the one-minute CI slice) from seed `RACEWAY_FUZZ_SEED`
//! (default: fixed, so CI is reproducible); `scripts/fuzz --minutes N` runs them longer
//! with fresh seeds and prints the tallies. A failure prints the seed and case number that
//! reproduce it.
//!
//! The generator is a small xorshift (no new dependency): shrinking is by hand, from the
//! seed printed.

#[path = "common/capi_observe.rs"]
mod capi_observe;
use capi_observe::{message, observe};
use raceway::capi::*;
use raceway::report::thread_cpu_s as thread_cpu;
use std::ffi::{c_char, CString};
use std::ptr::null_mut;
use std::time::{Duration, Instant};

/// A case taking more thread CPU time than this counts as a hang.
const HANG_SECONDS: f64 = 5.0;

/// The thread stack every campaign runs on: the 64 KiB an instance is promised to need
/// at most (docs/reliability.md), so a deep parse or schema walk shows as a crash here.
const STACK: usize = 64 * 1024;

/// `f` on a fresh thread of [`STACK`] bytes (a stack overflow aborts the test process:
/// the campaign then reports no tally, which `scripts/fuzz` counts as a crash).
fn on_small_stack(f: fn()) {
    std::thread::Builder::new()
        .name("fuzz-64k".into())
        .stack_size(STACK)
        .spawn(f)
        .expect("spawn a 64 KiB thread")
        .join()
        .unwrap_or_else(|e| std::panic::resume_unwind(e));
}

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        // xorshift64* (Vigna 2016)
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn chance(&mut self, p: f64) -> bool {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64 <= p
    }
    /// A nasty or ordinary number.
    fn number(&mut self) -> f64 {
        const NASTY: [f64; 14] = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.0,
            -0.0,
            5e-324,
            1e-300,
            -1e-200,
            1e300,
            -1e308,
            f64::MAX,
            1.0,
            -1.0,
            1e18,
        ];
        if self.chance(0.3) {
            NASTY[self.below(NASTY.len())]
        } else {
            let m = (self.next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            m * 10f64.powi(self.below(12) as i32 - 8)
        }
    }
}

fn budget() -> Duration {
    let s: f64 = std::env::var("RACEWAY_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(25.0);
    Duration::from_secs_f64(s)
}

fn seed() -> u64 {
    std::env::var("RACEWAY_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5eed_1234_abcd_0001)
}

#[derive(Default, Debug)]
struct Tally {
    cases: u64,
    accepted: u64,
    refused: u64,
    panics: u64,
    hangs: u64,
    nans: u64,
    unclear: u64,
    slowest_s: f64,
}

impl Tally {
    /// Records a case's thread CPU time; true when it counts as a hang.
    fn timed(&mut self, secs: f64) -> bool {
        self.slowest_s = self.slowest_s.max(secs);
        let hang = secs > HANG_SECONDS;
        self.hangs += u64::from(hang);
        hang
    }
    fn report(&self, what: &str, seed: u64, secs: f64) {
        println!(
            "fuzz {what}: seed {seed} for {secs:.0} s (wall): {} cases ({} accepted, {} refused), \
             {} panics, {} hangs (> {HANG_SECONDS} s), {} NaN/inf, {} unclear messages, \
             slowest case {:.2} s of CPU",
            self.cases,
            self.accepted,
            self.refused,
            self.panics,
            self.hangs,
            self.nans,
            self.unclear,
            self.slowest_s
        );
    }
    fn clean(&self) -> bool {
        self.panics == 0 && self.hangs == 0 && self.nans == 0 && self.unclear == 0
    }
}

/// A refusal message is clear when it is non-empty text that says more than a status.
fn clear(msg: &str) -> bool {
    msg.len() >= 12 && !msg.contains("unknown panic")
}

// ------------------------------------------------------------------ scenes

const SCENES: [&str; 4] = [
    raceway::component::scene::DEFAULT_SCENE,
    include_str!("../examples/scenes/6205-linear.toml"),
    include_str!("../examples/scenes/6205-ring2-radial.toml"),
    include_str!("../examples/scenes/7008ce-qs-motion.toml"),
];

/// Mutate scene text: replace a number, delete a line, duplicate a line, flip a byte,
/// nest a value deeply (or write a header of many dotted parts), swap a value for an
/// array or a table.
fn mutate(rng: &mut Rng, text: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(3) {
        if lines.is_empty() {
            break;
        }
        let i = rng.below(lines.len());
        match rng.below(7) {
            0 | 1 => {
                // A number replaced (the first run of digits on the line).
                let l = &lines[i];
                if let Some(a) = l.find(|c: char| c.is_ascii_digit()) {
                    let b = l[a..]
                        .find(|c: char| !(c.is_ascii_digit() || ".eE-+".contains(c)))
                        .map_or(l.len(), |k| a + k);
                    let x = rng.number();
                    let v = if x.is_nan() {
                        "nan".to_string()
                    } else if x.is_infinite() {
                        if x > 0.0 { "inf" } else { "-inf" }.to_string()
                    } else {
                        format!("{x:e}")
                    };
                    lines[i] = format!("{}{v}{}", &l[..a], &l[b..]);
                }
            }
            2 => {
                lines.remove(i);
            }
            3 => {
                let l = lines[i].clone();
                lines.insert(i, l);
            }
            4 => {
                let mut b = lines[i].clone().into_bytes();
                if !b.is_empty() {
                    let k = rng.below(b.len());
                    b[k] = b" =[]{}\".,0-9aznx#"[rng.below(17)];
                }
                lines[i] = String::from_utf8_lossy(&b).into_owned();
            }
            5 => {
                // Deep nesting (issue #38 item 1): a value inside up to 400 arrays or
                // inline tables, or a header of up to 100 000 dotted parts.
                let depth = 1 + rng.below(400);
                if let Some(eq) = lines[i].find('=') {
                    let v = lines[i][eq + 1..].trim().to_string();
                    let (open, close) = if rng.chance(0.5) {
                        ("[", "]")
                    } else {
                        ("{ x = ", " }")
                    };
                    lines[i] = format!(
                        "{}= {}{v}{}",
                        &lines[i][..eq],
                        open.repeat(depth),
                        close.repeat(depth)
                    );
                } else {
                    let parts = 1 + rng.below(100_000);
                    lines[i] = format!("[{}]", vec!["a"; parts].join("."));
                }
            }
            _ => {
                if let Some(eq) = lines[i].find('=') {
                    let v = lines[i][eq + 1..].trim().to_string();
                    let wrapped = if rng.chance(0.5) {
                        format!("[{v}]")
                    } else {
                        format!("{{ x = {v} }}")
                    };
                    lines[i] = format!("{}= {wrapped}", &lines[i][..eq]);
                }
            }
        }
    }
    lines.join("\n") + "\n"
}

#[test]
fn fuzz_scenes_through_the_component() {
    on_small_stack(scenes_campaign);
}

fn scenes_campaign() {
    let seed0 = seed();
    let mut rng = Rng(seed0 | 1);
    let mut tally = Tally::default();
    let start = Instant::now();
    while start.elapsed() < budget() {
        let case = tally.cases;
        tally.cases += 1;
        let base = SCENES[rng.below(SCENES.len())];
        let text = mutate(&mut rng, base);
        if std::env::var_os("RACEWAY_FUZZ_TRACE").is_some() {
            eprintln!("case {case}:\n{text}");
        }
        let t0 = thread_cpu();
        let r = std::panic::catch_unwind(|| {
            let mut c = match raceway::component::Component::from_text(&text) {
                Ok(c) => c,
                Err(e) => return Err(e.to_string()),
            };
            // Inputs the scene leaves unset are set to their initial value (0).
            for v in raceway::component::variables::all() {
                if v.is_input(c.causality()) {
                    let x = c.get_real(v.vr).map_err(|e| e.to_string())?;
                    c.set_real(v.vr, x).map_err(|e| e.to_string())?;
                }
            }
            let h = 1e-4;
            for k in 0..3 {
                if let Err(e) = c.do_step(k as f64 * h, h) {
                    return Err(e.to_string());
                }
            }
            let bad = (0..raceway::component::n_variables() as u32)
                .filter_map(|i| {
                    c.get_real(raceway::component::variables::all().nth(i as usize)?.vr)
                        .ok()
                })
                .any(|v| !v.is_finite());
            Ok(bad)
        });
        let secs = thread_cpu() - t0;
        if tally.timed(secs) {
            eprintln!("hang: seed {seed0} case {case} ({secs:.1} s):\n{text}");
        }
        match r {
            Err(_) => {
                tally.panics += 1;
                eprintln!("panic: seed {seed0} case {case}:\n{text}");
            }
            Ok(Ok(nan)) => {
                tally.accepted += 1;
                if nan {
                    tally.nans += 1;
                    eprintln!("NaN output: seed {seed0} case {case}:\n{text}");
                }
            }
            Ok(Err(msg)) => {
                tally.refused += 1;
                if !clear(&msg) {
                    tally.unclear += 1;
                    eprintln!("unclear message `{msg}`: seed {seed0} case {case}:\n{text}");
                }
            }
        }
    }
    tally.report("scenes", seed0, start.elapsed().as_secs_f64());
    assert!(tally.cases > 0 && tally.clean(), "{tally:?}");
}

// ------------------------------------------------------------------ C ABI

const MOTION_SCENE: &str = "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -8e-6, \"shaft.z\" = 0.0, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 0.0, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0 }\n";

/// A handle pool: live, freed and made-up handles side by side.
struct Pool {
    insts: Vec<*mut RacewayComponent>,
    live: usize,
    states: Vec<*mut RacewayState>,
    bytes: Vec<Vec<u8>>,
}

#[test]
fn fuzz_c_abi_call_sequences() {
    on_small_stack(c_abi_campaign);
}

fn c_abi_campaign() {
    let seed0 = seed() ^ 0xc0ffee;
    let mut rng = Rng(seed0 | 1);
    let mut tally = Tally::default();
    let scene = CString::new(MOTION_SCENE).unwrap();
    let default = CString::new(raceway::component::scene::DEFAULT_SCENE).unwrap();
    let start = Instant::now();
    let mut pool = Pool {
        insts: vec![],
        live: 0,
        states: vec![],
        bytes: vec![],
    };
    let vr_pool: Vec<u32> = (0..raceway_variable_count())
        .map(|i| {
            let mut vr = 0;
            unsafe { raceway_variable_at(i, &mut vr) };
            vr
        })
        .chain([u32::MAX, 0, 77777])
        .collect();
    while start.elapsed() < budget() {
        let case = tally.cases;
        tally.cases += 1;
        let pick_inst = |rng: &mut Rng, pool: &Pool| -> *mut RacewayComponent {
            match rng.below(20) {
                0 => null_mut(),
                1 => (rng.next() as usize & !0xf) as *mut RacewayComponent,
                _ if !pool.insts.is_empty() => pool.insts[rng.below(pool.insts.len())],
                _ => null_mut(),
            }
        };
        let c = pick_inst(&mut rng, &pool);
        let before = observe(c);
        let t0 = thread_cpu();
        let op = rng.below(12);
        let status = unsafe {
            match op {
                0 => {
                    if pool.live < 3 {
                        let mut err = [0 as c_char; 256];
                        let text = if rng.chance(0.5) { &scene } else { &default };
                        let p = raceway_create(text.as_ptr(), err.as_mut_ptr(), err.len());
                        assert!(!p.is_null());
                        pool.insts.push(p);
                        pool.live += 1;
                    }
                    RacewayStatus::Ok
                }
                1 => {
                    // free (live, freed, made-up: all must be safe); handles stay in the
                    // pool, so later calls use freed handles too.
                    if observe(c).is_some() {
                        pool.live -= 1;
                    }
                    raceway_free(c);
                    if pool.insts.len() > 8 {
                        // Forget the oldest handle (freed first when live).
                        let old = pool.insts.remove(0);
                        if observe(old).is_some() {
                            pool.live -= 1;
                            raceway_free(old);
                        }
                    }
                    RacewayStatus::Ok
                }
                2 | 3 => {
                    let n = rng.below(13);
                    let vrs: Vec<u32> = (0..n).map(|_| vr_pool[rng.below(vr_pool.len())]).collect();
                    let vals: Vec<f64> = (0..n)
                        .map(|_| {
                            if rng.chance(0.8) {
                                1e-7 * rng.number().clamp(-10.0, 10.0)
                            } else {
                                rng.number()
                            }
                        })
                        .collect();
                    raceway_set_reals(c, vrs.as_ptr(), vals.as_ptr(), n)
                }
                4 | 5 => {
                    let mut t = 0.0;
                    raceway_get_time(c, &mut t);
                    let h = if rng.chance(0.8) { 1e-4 } else { rng.number() };
                    let t = if rng.chance(0.8) { t } else { rng.number() };
                    raceway_do_step(c, t, h)
                }
                6 => {
                    let n = rng.below(10);
                    let vrs: Vec<u32> = (0..n).map(|_| vr_pool[rng.below(vr_pool.len())]).collect();
                    let mut out = vec![0.0; n];
                    let st = raceway_get_reals(c, vrs.as_ptr(), out.as_mut_ptr(), n);
                    if st == RacewayStatus::Ok && out.iter().any(|v| !v.is_finite()) {
                        tally.nans += 1;
                        eprintln!("NaN read: seed {seed0} case {case}");
                    }
                    st
                }
                7 => {
                    let mut s = if !pool.states.is_empty() && rng.chance(0.5) {
                        pool.states[rng.below(pool.states.len())]
                    } else {
                        null_mut()
                    };
                    let st = raceway_state_get(c, &mut s);
                    if st == RacewayStatus::Ok && !pool.states.contains(&s) {
                        pool.states.push(s);
                        if pool.states.len() > 16 {
                            raceway_state_free(pool.states.remove(0));
                        }
                    }
                    st
                }
                8 if !pool.states.is_empty() => {
                    let s = pool.states[rng.below(pool.states.len())];
                    if rng.chance(0.3) {
                        raceway_state_free(s);
                        RacewayStatus::Ok
                    } else {
                        raceway_state_set(c, s)
                    }
                }
                9 if !pool.states.is_empty() => {
                    let s = pool.states[rng.below(pool.states.len())];
                    let mut n = 0usize;
                    let st = raceway_state_size(c, s, &mut n);
                    if st != RacewayStatus::Ok {
                        st
                    } else {
                        let mut b = vec![0u8; n];
                        let st = raceway_state_serialize(c, s, b.as_mut_ptr(), n);
                        if st == RacewayStatus::Ok {
                            pool.bytes.push(b);
                            if pool.bytes.len() > 8 {
                                pool.bytes.remove(0);
                            }
                        }
                        st
                    }
                }
                10 if !pool.bytes.is_empty() => {
                    let mut b = pool.bytes[rng.below(pool.bytes.len())].clone();
                    match rng.below(4) {
                        0 => b.truncate(rng.below(b.len() + 1)),
                        1 => {
                            let k = rng.below(b.len());
                            b[k] ^= 1 << rng.below(8);
                        }
                        2 => {
                            let k = rng.below(b.len() / 8) * 8;
                            b[k..k + 8].copy_from_slice(&f64::NAN.to_le_bytes());
                        }
                        _ => {}
                    }
                    let mut s = null_mut();
                    let st = raceway_state_deserialize(c, b.as_ptr(), b.len(), &mut s);
                    if st == RacewayStatus::Ok {
                        let st = raceway_state_set(c, s);
                        raceway_state_free(s);
                        st
                    } else {
                        assert!(s.is_null());
                        st
                    }
                }
                _ => {
                    let mut v = 0.0;
                    let st = raceway_get_real(c, vr_pool[rng.below(vr_pool.len())], &mut v);
                    if st == RacewayStatus::Ok && !v.is_finite() {
                        tally.nans += 1;
                        eprintln!("NaN read: seed {seed0} case {case}");
                    }
                    st
                }
            }
        };
        let secs = thread_cpu() - t0;
        if tally.timed(secs) {
            eprintln!("hang: seed {seed0} case {case} op {op} ({secs:.1} s)");
        }
        match status {
            RacewayStatus::Ok => tally.accepted += 1,
            RacewayStatus::Panic => {
                tally.panics += 1;
                eprintln!("panic: seed {seed0} case {case} op {op}: {}", message(c));
            }
            other => {
                tally.refused += 1;
                let m = message(c);
                let bare = matches!(
                    other,
                    RacewayStatus::NullPointer | RacewayStatus::InvalidHandle
                );
                if !bare && !clear(&m) {
                    tally.unclear += 1;
                    eprintln!(
                        "unclear message `{m}` ({other:?}): seed {seed0} case {case} op {op}"
                    );
                }
                // A refused call changes nothing (a state restore that was refused, a
                // failed step, a refused set).
                if op != 1 {
                    let after = observe(c);
                    if before.is_some() && after != before {
                        tally.unclear += 1;
                        eprintln!(
                            "refused call changed the instance: seed {seed0} case {case} op {op}"
                        );
                    }
                }
            }
        }
        // Outputs after a successful call are finite.
        if status == RacewayStatus::Ok {
            if let Some(v) = observe(c) {
                if v.iter().any(|b| !f64::from_bits(*b).is_finite()) {
                    tally.nans += 1;
                    eprintln!("non-finite value after op {op}: seed {seed0} case {case}");
                }
            }
        }
    }
    unsafe {
        for &c in &pool.insts {
            raceway_free(c);
        }
        for &s in &pool.states {
            raceway_state_free(s);
        }
    }
    tally.report("C ABI", seed0, start.elapsed().as_secs_f64());
    assert!(tally.cases > 0 && tally.clean(), "{tally:?}");
}

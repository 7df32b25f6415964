//! No heap allocation while stepping: a counting global allocator (counting only on the
//! thread that opts in, so the test harness's own allocations do not count) around
//! `integrate` calls on integrators that were constructed beforehand.

use nalgebra::DMatrix;
use raceway::solver::{BlockArrowhead, Dopri5, Integrator, OdeSystem, Options, Rosenbrock};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<u64> = const { Cell::new(0) };
}

fn note() {
    // `try_with`: thread-locals may be gone while a thread shuts down
    let _ = COUNTING.try_with(|c| {
        if c.get() {
            let _ = COUNT.try_with(|n| n.set(n.get() + 1));
        }
    });
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `f` on this thread.
fn allocations(f: impl FnOnce()) -> u64 {
    COUNT.with(|n| n.set(0));
    COUNTING.with(|c| c.set(true));
    f();
    COUNTING.with(|c| c.set(false));
    COUNT.with(|n| n.get())
}

/// Stiff, non-autonomous, arrowhead-structured test system (3 "balls" of 2 states on a
/// 2-state "ring"); optionally with an analytic Jacobian.
struct Sys {
    analytic: bool,
}
impl OdeSystem for Sys {
    fn dim(&self) -> usize {
        8
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        let mut force = 0.0;
        for b in 0..3 {
            let d = y[2 * b] - y[6];
            let f = 1e3 * d + 1e2 * d * d * d;
            dy[2 * b] = y[2 * b + 1];
            dy[2 * b + 1] = -f - 1e3 * y[2 * b + 1] + (t + b as f64).sin();
            force += f;
        }
        dy[6] = y[7];
        dy[7] = force / 3.0 - 10.0 * y[6] - y[7];
        Ok(())
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut DMatrix<f64>) -> bool {
        if !self.analytic {
            return false;
        }
        j.fill(0.0);
        let mut sum = 0.0;
        for b in 0..3 {
            let d = y[2 * b] - y[6];
            let fp = 1e3 + 3e2 * d * d;
            j[(2 * b, 2 * b + 1)] = 1.0;
            j[(2 * b + 1, 2 * b)] = -fp;
            j[(2 * b + 1, 2 * b + 1)] = -1e3;
            j[(2 * b + 1, 6)] = fp;
            j[(7, 2 * b)] = fp / 3.0;
            sum += fp;
        }
        j[(6, 7)] = 1.0;
        j[(7, 6)] = -sum / 3.0 - 10.0;
        j[(7, 7)] = -1.0;
        true
    }
}

#[test]
fn integrating_allocates_nothing_after_construction() {
    let n = 8;
    let y0: Vec<f64> = (0..n).map(|i| 0.01 * (i as f64).cos()).collect();
    let adaptive = Options::new(n, 1e-6, 1e-9);
    let fixed = Options::fixed(n, 1e-3);
    let mut integrators = [
        ("DOPRI5", Integrator::Dopri5(Dopri5::new(n)), false),
        (
            "RODAS4 dense LU, FD Jacobian",
            Integrator::Rosenbrock(Rosenbrock::new(n)),
            false,
        ),
        (
            "RODAS4 dense LU, analytic Jacobian",
            Integrator::Rosenbrock(Rosenbrock::new(n)),
            true,
        ),
        (
            "RODAS4 block-arrowhead",
            Integrator::Rosenbrock(Rosenbrock::with_solver(Box::new(BlockArrowhead::new(
                3, 2, 2,
            )))),
            true,
        ),
    ];
    for (name, integ, analytic) in integrators.iter_mut() {
        let mut sys = Sys {
            analytic: *analytic,
        };
        let mut y = y0.clone();
        let mut h = 0.0;
        let mut out = vec![0.0; n];
        let count = allocations(|| {
            // many communication steps, cold then warm step size, adaptive and fixed
            for k in 0..20 {
                let (t0, t1) = (0.05 * k as f64, 0.05 * (k + 1) as f64);
                integ
                    .integrate(&mut sys, t0, t1, &mut y, &mut h, &adaptive)
                    .unwrap();
                let (a, b) = integ.last_step().unwrap();
                integ.dense(0.5 * (a + b), &mut out).unwrap();
            }
            integ
                .integrate(&mut sys, 1.0, 1.01, &mut y, &mut h, &fixed)
                .unwrap();
        });
        let stats = *integ.stats();
        println!("{name}: {count} allocations, {stats:?}");
        assert!(stats.accepted > 20 && stats.rhs_evals > 100);
        assert_eq!(count, 0, "{name} allocated while integrating");
    }
    // the counter works: an allocation is seen
    let count = allocations(|| {
        std::hint::black_box(vec![1u8; 16]);
    });
    assert_eq!(count, 1);
}

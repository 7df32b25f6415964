//! `do_step` performs no heap allocation once running (a counting global allocator).

use raceway::component::Component;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static ALLOCS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        ALLOCS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 {
        ALLOCS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(p, l, n) }
    }
}

#[global_allocator]
static A: Counting = Counting;

fn allocations_in_steps(scene: &str, h: f64) -> usize {
    let mut c = Component::from_text(scene).unwrap();
    for i in 0..3 {
        c.do_step(i as f64 * h, h).unwrap();
    }
    let before = ALLOCS.load(Ordering::SeqCst);
    for i in 3..50 {
        c.do_step(i as f64 * h, h).unwrap();
    }
    ALLOCS.load(Ordering::SeqCst) - before
}

// One test function: the counter is process-wide and tests run on threads.
#[test]
fn do_step_does_not_allocate() {
    for scene in [
        "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -8e-6, \"shaft.z\" = 0.0, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 1e-4, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0, \"shaft.omega\" = 183.26 }\n",
        "bearing = \"7008ce\"\n[model]\nlevel = \"quasi_static\"\n[inputs]\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -3e-6, \"shaft.z\" = 10e-6, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 0.0, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0, \"shaft.omega\" = 2000.0 }\n",
        "bearing = \"6205\"\n[model]\nlevel = \"quasi_static\"\ncausality = \"load\"\n[inputs]\ninitial = { \"load.x\" = 0.0, \"load.y\" = -500.0, \"load.z\" = 0.0, \"load.mx\" = 0.0, \"load.my\" = 0.0, \"shaft.omega\" = 183.26 }\n",
        "bearing = \"6205\"\n[model]\nlevel = \"linear\"\ncausality = \"load\"\ncontact_damping = 100.0\n[inputs]\ninitial = { \"load.x\" = 0.0, \"load.y\" = -900.0, \"load.z\" = 0.0, \"load.mx\" = 0.0, \"load.my\" = 0.0, \"shaft.omega\" = 183.26 }\n",
        "bearing = \"7008ce\"\n[model]\nlevel = \"ring\"\nring_dof = 5\ncausality = \"load\"\ncontact_damping = 500.0\n[inputs]\ninitial = { \"load.x\" = 0.0, \"load.y\" = -300.0, \"load.z\" = 200.0, \"load.mx\" = 0.0, \"load.my\" = 0.0, \"shaft.omega\" = 600.0 }\n",
        "bearing = \"7004\"\n[model]\nlevel = \"full\"\n[inputs]\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -2.96568e-6, \"shaft.z\" = 4.364864e-5, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 0.0, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0, \"shaft.omega\" = 3141.59 }\n",
    ] {
        assert_eq!(allocations_in_steps(scene, 1e-4), 0, "{scene}");
    }
}

//! Helpers shared by the test modules: loading robots for the runtime path, a comparison
//! helper, and the counting global allocator behind the "allocates nothing" tests.

use dhgen::Robot;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::PathBuf;

/// A catalogue robot, `robots/<name>.toml`, for the runtime path.
pub fn runtime(name: &str) -> Robot {
    Robot::from_toml_file(format!("{}/robots/{name}.toml", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// `model` at another scale: lengths (a, the revolute joints' d, the prismatic joints'
/// limits, base and tool positions, centres of mass) times `length`, link masses times
/// `mass` and their inertia tensors times `mass · length²`; motors and friction as they are.
pub fn scaled(mut model: dhgen::RobotModel, length: f64, mass: f64) -> dhgen::RobotModel {
    for l in &mut model.links {
        l.a *= length;
        if l.joint == dhgen::JointKind::Revolute {
            l.d *= length;
        } else if let Some(limits) = &mut l.limits {
            limits.iter_mut().for_each(|x| *x *= length);
        }
        if let Some(i) = &mut l.inertial {
            i.mass *= mass;
            i.com.iter_mut().for_each(|x| *x *= length);
            i.inertia
                .iter_mut()
                .flatten()
                .for_each(|x| *x *= mass * length * length);
        }
    }
    for pose in [&mut model.base, &mut model.tool].into_iter().flatten() {
        pose.xyz.iter_mut().for_each(|x| *x *= length);
    }
    model
}

/// The path of the fixture `tests/fixtures/<name>.toml`.
pub fn fixture_path(name: &str) -> PathBuf {
    PathBuf::from(format!(
        "{}/tests/fixtures/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
}

/// The fixture `tests/fixtures/<name>.toml`, for the runtime path.
pub fn fixture(name: &str) -> Robot {
    Robot::from_toml_file(fixture_path(name)).unwrap()
}

/// Every TOML description of the repository: the catalogue (`robots/`), then the fixtures
/// (`tests/fixtures/`), each directory in name order.
pub fn description_paths() -> Vec<PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut all = Vec::new();
    for dir in ["robots", "tests/fixtures"] {
        let mut paths: Vec<_> = std::fs::read_dir(root.join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        paths.sort();
        all.extend(paths);
    }
    all
}

/// Pinocchio's reference values for the catalogue robot `name` (`puma560` or `panda`):
/// tests/data/derivatives_<name>.json, made by scripts/pinocchio_derivatives.py.
pub fn pinocchio_reference(name: &str) -> serde_json::Value {
    let path = format!(
        "{}/tests/data/derivatives_{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The largest magnitude among `values` (0 for none).
pub fn max_abs(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().map(f64::abs).fold(0.0, f64::max)
}

/// Counts the heap allocations made by each thread (tests run on several threads), to check
/// that code paths allocate nothing: see [`allocations_during`].
struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// A counting global allocator is the one way to prove "no allocation": it must implement the
// unsafe `GlobalAlloc` trait, delegating to the system allocator.
#[expect(
    unsafe_code,
    reason = "a GlobalAlloc that counts and delegates to System"
)]
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // try_with: the thread-local may already be gone while a thread shuts down.
        let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// A configuration drawn uniformly within the joint limits ([−3, 3] for a joint without).
pub fn random_q<A: dhgen::Arm>(
    arm: &A,
    rng: &mut rand::rngs::StdRng,
) -> dhgen::nalgebra::OVector<f64, A::Dof>
where
    dhgen::nalgebra::DefaultAllocator: dhgen::ArmAllocator<A::Dof>,
{
    use rand::RngExt;
    dhgen::nalgebra::OVector::<f64, A::Dof>::from_fn_generic(
        arm.dim(),
        dhgen::nalgebra::U1,
        |j, _| {
            let [lo, hi] = arm.limits(j).unwrap_or([-3.0, 3.0]);
            rng.random_range(lo..=hi)
        },
    )
}

/// Runs `f` and returns how many allocations it made on this thread.
pub fn allocations_during(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

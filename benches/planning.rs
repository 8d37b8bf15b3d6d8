//! Path planning on the PUMA 560 scene of the tests (a table, a panel and a ball), the
//! generated module against the runtime `dhgen::Robot`:
//!
//! - `planning/collision_check/{generated|runtime}`: one configuration checked against the
//!   scene ([`CollisionChecker::is_free`] with the local planner's margin), cycling through
//!   64 fixed random configurations; throughput in checks per second;
//! - `planning/roadmap/{generated|runtime}`: a roadmap of 100 nodes sampled and connected
//!   to their 10 nearest neighbours at 0.02 rad (6.4.1 and 6.4.2); throughput in nodes per
//!   second. The collision checks one roadmap needs are printed first, to convert.
//!
//! `cargo bench --bench planning`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use dhgen::nalgebra::{DVector, SVector};
use dhgen::planning::{CollisionChecker, Prm, PrmConfig, Scene};
use dhgen::{Arm, ArmAllocator, JointVector, Robot};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::hint::black_box;
use std::time::Duration;

#[path = "../tests/integration/planning_support.rs"]
pub mod scenes;

dhgen::robot!(mod puma560 = "robots/puma560.toml");

const STATES: usize = 64;
const NODES: usize = 100;

fn roadmap_config() -> PrmConfig {
    PrmConfig {
        initial_nodes: NODES,
        max_nodes: NODES,
        neighbours: 10,
        resolution: 0.02,
        ..PrmConfig::default()
    }
}

fn checker<A: Arm>(arm: &A) -> CollisionChecker<'_, A>
where
    dhgen::nalgebra::DefaultAllocator: ArmAllocator<A::Dof>,
{
    CollisionChecker::new(arm, Scene::new(scenes::puma_obstacles()).unwrap()).unwrap()
}

fn configurations(checker: &CollisionChecker<'_, puma560::Robot>) -> Vec<[f64; 6]> {
    let mut rng = StdRng::seed_from_u64(7);
    (0..STATES)
        .map(|_| {
            core::array::from_fn(|j| {
                let [lo, hi] = checker.joint_range(j);
                rng.random_range(lo..hi)
            })
        })
        .collect()
}

fn bench_checks<A: Arm>(c: &mut Criterion, name: &str, arm: &A, qs: &[JointVector<A>], margin: f64)
where
    dhgen::nalgebra::DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut checker = checker(arm);
    let mut group = c.benchmark_group("planning/collision_check");
    group.throughput(Throughput::Elements(1));
    group.bench_function(BenchmarkId::from_parameter(name), |b| {
        let mut k = 0;
        b.iter(|| {
            k = (k + 1) % qs.len();
            black_box(checker.is_free(black_box(&qs[k]), margin))
        })
    });
    group.finish();
}

fn bench_roadmap<A: Arm>(c: &mut Criterion, name: &str, arm: &A)
where
    dhgen::nalgebra::DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut checker = checker(arm);
    {
        let mut prm = Prm::new(&mut checker, roadmap_config(), 0).unwrap();
        prm.build();
        let s = prm.stats();
        println!(
            "{name}: a roadmap of {} nodes, {} edges ({} local-planner calls) takes {} collision checks",
            s.nodes, s.edges, s.edge_attempts, s.collision_checks
        );
    }
    let mut group = c.benchmark_group("planning/roadmap");
    group.throughput(Throughput::Elements(NODES as u64));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(10));
    let mut seed = 0;
    group.bench_function(BenchmarkId::from_parameter(name), |b| {
        b.iter(|| {
            seed += 1;
            let mut prm = Prm::new(&mut checker, roadmap_config(), seed).unwrap();
            prm.build();
            black_box(prm.stats().edges)
        })
    });
    group.finish();
}

fn planning(c: &mut Criterion) {
    let robot = Robot::from_model(scenes::model("puma560.toml"));
    let margin = checker(&puma560::Robot)
        .model()
        .margin(roadmap_config().resolution);
    let qs = configurations(&checker(&puma560::Robot));
    let generated: Vec<SVector<f64, 6>> = qs.iter().map(|q| SVector::from(*q)).collect();
    let runtime: Vec<DVector<f64>> = qs.iter().map(|q| DVector::from_column_slice(q)).collect();
    bench_checks(c, "generated", &puma560::Robot, &generated, margin);
    bench_checks(c, "runtime", &robot, &runtime, margin);
    bench_roadmap(c, "generated", &puma560::Robot);
    bench_roadmap(c, "runtime", &robot);
}

criterion_group!(benches, planning);
criterion_main!(benches);

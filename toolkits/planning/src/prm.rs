//! The probabilistic roadmap method (section 6.4), seeded and reproducible.
//!
//! 1. Sampling (6.4.1): configurations drawn uniformly within the joint ranges (limits, or
//!    `[−π, π]` for a revolute joint without limits); those that are not free are
//!    discarded.
//! 2. Connection (6.4.2): every node is joined to each of its `k` nearest nodes (Euclidean
//!    joint-space distance: a kd-tree, `kiddo`, for up to [`KD_TREE_DOF`] joints, an exact
//!    scan of every node beyond, where a kd-tree prunes little, and of the few nodes a
//!    kd-tree cannot hold) by the straight-line local planner
//!    [`CollisionChecker::motion_is_free`] at the stated `resolution`.
//! 3. Enhancement (6.4.3), while start and goal lie in different connected components and
//!    the budget allows: each smaller component tries to connect to the largest one through
//!    its node closest to it (the closest pairs first), then new nodes are sampled, mostly
//!    in a box around nodes with few neighbours (where narrow passages tend to be), the rest
//!    uniformly.
//! 4. Query: start and goal join the roadmap through the local planner, A* (`petgraph`,
//!    with the admissible straight-line heuristic) finds the shortest roadmap path, and
//!    random shortcutting (6.4.4) smooths it: two random points of the path are joined
//!    directly when the local planner allows, until `shortcut_attempts` tries in a row
//!    shorten it by less than 0.1 %; last, every waypoint whose neighbours can be joined
//!    directly is dropped.
//!
//! Every random choice comes from a ChaCha8 generator seeded by the caller, and every
//! iteration order is fixed, so a seed gives the same roadmap and path on every platform
//! (as long as no time budget cuts the work short).
//!
//! ```
//! use dhgen::planning::{CollisionChecker, Obstacle, Prm, PrmConfig, Scene};
//! use dhgen::nalgebra::SVector;
//! dhgen::robot!(mod planar = "../../robots/planar_elbow.toml");
//!
//! // Beyond the reach of link 1 (1 m), so link 2 has to fold to pass it.
//! let scene = Scene::new(vec![Obstacle::sphere([0.0, 1.4, 0.0], 0.2)]).unwrap();
//! let mut checker = CollisionChecker::new(&planar::Robot, scene).unwrap();
//! let mut prm = Prm::new(&mut checker, PrmConfig::default(), 7).unwrap();
//! let path = prm
//!     .query(&SVector::from([0.3, 0.2]), &SVector::from([2.8, -0.2]))
//!     .unwrap();
//! assert_eq!(path.waypoints[0], SVector::from([0.3, 0.2]));
//! assert!(checker.path_is_free(&path.waypoints, 0.02));
//! ```

use super::{CollisionChecker, PlanError};
use dhgen_kernel::{Arm, ArmAllocator, JointVector};
use kiddo::{MutableKdTree, QueryResultItem, SquaredEuclidean};
use nalgebra::{DefaultAllocator, U1};
use petgraph::graph::{NodeIndex, UnGraph};
use petgraph::unionfind::UnionFind;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::{Duration, Instant};

/// The most joints for which a roadmap finds nearest nodes with a kd-tree (built for a fixed
/// dimension); with more, it scans every node. Both find the same neighbours: the nearest,
/// equal distances in node order.
pub const KD_TREE_DOF: usize = 8;

/// Budgets and settings of a roadmap.
#[derive(Clone, Debug, PartialEq)]
pub struct PrmConfig {
    /// Free configurations sampled uniformly before the first connection round.
    pub initial_nodes: usize,
    /// Node budget: enhancement stops here, and a query that has not connected start and
    /// goal by then fails.
    pub max_nodes: usize,
    /// Sample budget: configurations drawn in all, free or not (guards against a space
    /// with hardly any free configurations).
    pub max_samples: usize,
    /// `k`: how many nearest nodes each node tries to connect to (≥ 1).
    pub neighbours: usize,
    /// Resolution of the local planner: the largest joint-space distance between two
    /// checked configurations of an edge (> 0). Sets the safety margin, see
    /// [`CollisionModel::margin`](super::CollisionModel::margin).
    pub resolution: f64,
    /// Nodes added per enhancement round (≥ 1).
    pub enhancement_nodes: usize,
    /// A node with fewer edges than this gets new samples around it.
    pub few_neighbours: usize,
    /// Half-width, per joint, of the box around a node that its new samples come from
    /// (> 0, at most `f64::MAX / 2`).
    pub resample_radius: f64,
    /// Closest node pairs tried per component when connecting components.
    pub connect_attempts: usize,
    /// Smoothing stops after this many shortcut tries in a row shortened nothing.
    pub shortcut_attempts: usize,
    /// Wall-clock budget of a query (roadmap construction included); `None` for none, and so
    /// is a budget beyond what the clock can represent (`Duration::MAX`).
    /// Hitting it makes the result depend on the machine's speed.
    pub time_budget: Option<Duration>,
}

impl Default for PrmConfig {
    /// 100 initial nodes, at most 2000 nodes and 200 000 samples, k = 10, resolution
    /// 0.02, 50 nodes per enhancement round, resampling around nodes with fewer than 3
    /// edges within ±0.3, 5 connection tries per component, 50 shortcut tries, no time
    /// budget.
    fn default() -> Self {
        PrmConfig {
            initial_nodes: 100,
            max_nodes: 2000,
            max_samples: 200_000,
            neighbours: 10,
            resolution: 0.02,
            enhancement_nodes: 50,
            few_neighbours: 3,
            resample_radius: 0.3,
            connect_attempts: 5,
            shortcut_attempts: 50,
            time_budget: None,
        }
    }
}

impl PrmConfig {
    fn check(&self) -> Result<(), PlanError> {
        let bad = |name, reason: String| Err(PlanError::InvalidParameter { name, reason });
        for (name, x) in [
            ("resolution", self.resolution),
            ("resample_radius", self.resample_radius),
        ] {
            if !(x > 0.0 && x.is_finite()) {
                return bad(name, format!("{x} is not a finite number > 0"));
            }
        }
        // Samples are drawn from [−resample_radius, resample_radius]: its width must be a
        // number.
        if !(2.0 * self.resample_radius).is_finite() {
            return bad(
                "resample_radius",
                format!(
                    "{} is too large: the box ±resample_radius must have a finite width",
                    self.resample_radius
                ),
            );
        }
        for (name, x) in [
            ("neighbours", self.neighbours),
            ("enhancement_nodes", self.enhancement_nodes),
        ] {
            if x == 0 {
                return bad(name, "must be at least 1".into());
            }
        }
        if self.max_nodes < self.initial_nodes {
            return bad(
                "max_nodes",
                format!(
                    "{} is below initial_nodes = {}",
                    self.max_nodes, self.initial_nodes
                ),
            );
        }
        Ok(())
    }
}

/// Counters of a roadmap.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PrmStats {
    /// Nodes (start and goal of queries included).
    pub nodes: usize,
    /// Edges.
    pub edges: usize,
    /// Connected components.
    pub components: usize,
    /// Configurations sampled.
    pub samples: usize,
    /// Sampled configurations that were not free.
    pub rejected_samples: usize,
    /// Local-planner calls for edges.
    pub edge_attempts: usize,
    /// Configurations checked by the collision checker for this roadmap.
    pub collision_checks: u64,
    /// Enhancement rounds.
    pub enhancement_rounds: usize,
    /// Time spent building and enhancing the roadmap and answering queries.
    pub time: Duration,
}

/// A path found on a roadmap.
#[derive(Clone, Debug, PartialEq)]
pub struct PrmPath<V> {
    /// Waypoints from start to goal; the straight segments between them are free.
    pub waypoints: Vec<V>,
    /// Joint-space length of the smoothed path.
    pub length: f64,
    /// Joint-space length of the roadmap path before smoothing.
    pub roadmap_length: f64,
    /// Shortcuts taken by smoothing.
    pub shortcuts: usize,
    /// The roadmap's counters after the query.
    pub stats: PrmStats,
}

/// The node configurations, searched for nearest neighbours: by a kd-tree for the arm's
/// number of joints up to [`KD_TREE_DOF`], and by a scan of the points it does not hold
/// (all of them beyond [`KD_TREE_DOF`] joints; those it refused below: `kiddo` cannot split a
/// bucket of more than 32 points that share a coordinate, such as samples clamped to one
/// joint limit).
struct NodeTree {
    dim: usize,
    kd: Option<Kd>,
    /// The points not in the kd-tree, `dim` coordinates each, and their nodes.
    points: Vec<f64>,
    items: Vec<usize>,
}

/// A kd-tree for the arm's number of joints; its items are the nodes.
type KdTree<const K: usize> = MutableKdTree<f64, K>;

/// A kd-tree for the arm's number of joints.
enum Kd {
    D1(KdTree<1>),
    D2(KdTree<2>),
    D3(KdTree<3>),
    D4(KdTree<4>),
    D5(KdTree<5>),
    D6(KdTree<6>),
    D7(KdTree<7>),
    D8(KdTree<8>),
}

macro_rules! each_tree {
    ($tree:expr, $t:ident => $body:expr) => {
        match $tree {
            Kd::D1($t) => $body,
            Kd::D2($t) => $body,
            Kd::D3($t) => $body,
            Kd::D4($t) => $body,
            Kd::D5($t) => $body,
            Kd::D6($t) => $body,
            Kd::D7($t) => $body,
            Kd::D8($t) => $body,
        }
    };
}

fn point<const K: usize>(q: &[f64]) -> [f64; K] {
    core::array::from_fn(|i| q[i])
}

/// Adds node `item` at `q`; false where the tree refuses it (a node number beyond `u32`, or
/// a bucket it cannot split).
fn tree_add<const K: usize>(tree: &mut KdTree<K>, q: &[f64], item: usize) -> bool {
    u32::try_from(item).is_ok_and(|item| tree.add(&point::<K>(q), item).is_ok())
}

/// The `n` nearest, `0 < n ≤` the tree's size (kiddo asks for at least one).
fn tree_nearest<const K: usize>(tree: &KdTree<K>, q: &[f64], n: usize) -> Vec<(f64, usize)> {
    let query = point::<K>(q);
    let pairs = |found: Vec<QueryResultItem<(), u32, f64>>| -> Vec<(f64, usize)> {
        let mut found: Vec<(f64, usize)> = found
            .into_iter()
            .map(|nn| (nn.distance, nn.item as usize))
            .collect();
        found.sort_by(nearer);
        found
    };
    // One more than asked, to see whether nodes tie at the last distance taken: the tree
    // picks among those by its layout, so then all of them are fetched and the first in
    // node order kept. Equal distances in node order: the scan's answer, whatever the layout.
    let more = core::num::NonZeroUsize::MIN.saturating_add(n);
    let mut found = pairs(
        tree.query(&query)
            .nearest_n::<SquaredEuclidean<f64>>(more)
            .execute(),
    );
    if found.len() > n && found[n].0 == found[n - 1].0 {
        found = pairs(
            tree.query(&query)
                .within::<SquaredEuclidean<f64>>(found[n - 1].0)
                .unsorted()
                .execute(),
        );
    }
    found.truncate(n);
    found
}

/// Nearer first, equal distances in node order: `(squared distance, node)`.
fn nearer(a: &(f64, usize), b: &(f64, usize)) -> core::cmp::Ordering {
    a.0.total_cmp(&b.0).then(a.1.cmp(&b.1))
}

impl NodeTree {
    fn new(dim: usize) -> NodeTree {
        let kd = match dim {
            1 => Some(Kd::D1(KdTree::default())),
            2 => Some(Kd::D2(KdTree::default())),
            3 => Some(Kd::D3(KdTree::default())),
            4 => Some(Kd::D4(KdTree::default())),
            5 => Some(Kd::D5(KdTree::default())),
            6 => Some(Kd::D6(KdTree::default())),
            7 => Some(Kd::D7(KdTree::default())),
            8 => Some(Kd::D8(KdTree::default())),
            _ => None,
        };
        NodeTree {
            kd,
            ..NodeTree::scan(dim)
        }
    }

    /// Without a kd-tree: every query scans.
    fn scan(dim: usize) -> NodeTree {
        NodeTree {
            dim,
            kd: None,
            points: Vec::new(),
            items: Vec::new(),
        }
    }

    fn add(&mut self, q: &[f64], item: usize) {
        let held = self
            .kd
            .as_mut()
            .is_some_and(|kd| each_tree!(kd, t => tree_add(t, q, item)));
        if !held {
            self.points.extend_from_slice(q);
            self.items.push(item);
        }
    }

    /// How many points the kd-tree holds.
    fn in_tree(&self) -> usize {
        self.kd
            .as_ref()
            .map_or(0, |kd| each_tree!(kd, t => t.size()))
    }

    /// How many nodes it holds.
    fn len(&self) -> usize {
        self.in_tree() + self.items.len()
    }

    /// The `n` nearest nodes to `q`, nearest first: `(squared distance, node)`. The `n`
    /// nearest of the kd-tree's and the `n` nearest of the rest, merged.
    fn nearest(&self, q: &[f64], n: usize) -> Vec<(f64, usize)> {
        // No more than it holds (a `neighbours` of `usize::MAX` asks for everything).
        let n = n.min(self.len());
        if n == 0 {
            return Vec::new();
        }
        let mut found: Vec<(f64, usize)> = match &self.kd {
            Some(kd) if self.in_tree() > 0 => {
                each_tree!(kd, t => tree_nearest(t, q, n.min(self.in_tree())))
            }
            _ => Vec::new(),
        };
        if self.items.is_empty() {
            // The kd-tree holds every node: its answer is the answer.
            return found;
        }
        found.extend(
            self.points
                .chunks_exact(self.dim)
                .zip(&self.items)
                .map(|(p, &item)| (p.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum(), item)),
        );
        if n < found.len() {
            found.select_nth_unstable_by(n - 1, nearer);
            found.truncate(n);
        }
        found.sort_by(nearer);
        found
    }
}

/// A probabilistic roadmap for the arm of a [`CollisionChecker`].
pub struct Prm<'c, 'a, A: Arm>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    checker: &'c mut CollisionChecker<'a, A>,
    config: PrmConfig,
    rng: ChaCha8Rng,
    margin: f64,
    ranges: Vec<[f64; 2]>,
    nodes: Vec<JointVector<A>>,
    tree: NodeTree,
    graph: UnGraph<(), f64, u32>,
    components: UnionFind<usize>,
    stats: PrmStats,
    deadline: Option<Instant>,
}

impl<'c, 'a, A: Arm> Prm<'c, 'a, A>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    /// An empty roadmap; [`build`](Self::build) samples it, and [`query`](Self::query)
    /// builds it first if needed. `seed` fixes every random choice.
    pub fn new(
        checker: &'c mut CollisionChecker<'a, A>,
        config: PrmConfig,
        seed: u64,
    ) -> Result<Self, PlanError> {
        config.check()?;
        let dof = checker.dof();
        let tree = NodeTree::new(dof);
        Ok(Prm {
            margin: checker.model().margin(config.resolution),
            ranges: (0..dof).map(|j| checker.joint_range(j)).collect(),
            checker,
            config,
            rng: ChaCha8Rng::seed_from_u64(seed),
            nodes: Vec::new(),
            tree,
            graph: UnGraph::default(),
            components: UnionFind::new(0),
            stats: PrmStats::default(),
            deadline: None,
        })
    }

    /// The collision checker.
    pub fn checker(&mut self) -> &mut CollisionChecker<'a, A> {
        self.checker
    }

    /// The settings.
    pub fn config(&self) -> &PrmConfig {
        &self.config
    }

    /// The node configurations, indexed as in [`edges`](Self::edges).
    pub fn nodes(&self) -> &[JointVector<A>] {
        &self.nodes
    }

    /// The edges, as pairs of node indices.
    pub fn edges(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.graph
            .edge_indices()
            .filter_map(|e| self.graph.edge_endpoints(e))
            .map(|(a, b)| (a.index(), b.index()))
    }

    /// The component of every node, as the index of one representative node.
    pub fn component_labels(&self) -> Vec<usize> {
        (0..self.nodes.len())
            .map(|i| self.components.find(i))
            .collect()
    }

    /// The roadmap's counters.
    pub fn stats(&self) -> PrmStats {
        let mut stats = self.stats;
        stats.nodes = self.nodes.len();
        stats.edges = self.graph.edge_count();
        let mut roots: Vec<usize> = self.component_labels();
        roots.sort_unstable();
        roots.dedup();
        stats.components = roots.len();
        stats
    }

    /// When the time budget counted from `started` runs out; `None` without a budget or for
    /// one too long for `Instant` (`started + budget` would overflow and panic).
    fn deadline_from(&self, started: Instant) -> Option<Instant> {
        self.config.time_budget.and_then(|b| started.checked_add(b))
    }

    fn out_of_budget(&self) -> Option<String> {
        if self.nodes.len() >= self.config.max_nodes {
            Some(format!("node budget of {} reached", self.config.max_nodes))
        } else if self.stats.samples >= self.config.max_samples {
            Some(format!(
                "sample budget of {} reached",
                self.config.max_samples
            ))
        } else if self.deadline.is_some_and(|d| Instant::now() >= d) {
            Some(format!(
                "time budget of {:?} reached",
                self.config.time_budget.unwrap_or_default()
            ))
        } else {
            None
        }
    }

    fn add_node(&mut self, q: JointVector<A>) -> usize {
        let i = self.nodes.len();
        // A node at exactly the configuration of one in the tree (samples clamped to a joint
        // limit land on it again and again) is left out of the tree, whose kd-tree holds at
        // most 32 items at one point (beyond, they would be scanned); it still joins the
        // roadmap through its own neighbours, among them its twin.
        let twin = self
            .tree
            .nearest(q.as_slice(), 1)
            .first()
            .is_some_and(|&(d, _)| d == 0.0);
        if !twin {
            self.tree.add(q.as_slice(), i);
        }
        self.graph.add_node(());
        self.components.new_set();
        self.nodes.push(q);
        i
    }

    /// Tries the local planner between nodes `i` and `j`; adds the edge when it is free.
    fn try_edge(&mut self, i: usize, j: usize) -> bool {
        let (a, b) = (NodeIndex::new(i), NodeIndex::new(j));
        if i == j || self.graph.contains_edge(a, b) {
            return false;
        }
        self.stats.edge_attempts += 1;
        let (qi, qj) = (&self.nodes[i], &self.nodes[j]);
        if !self.checker.motion_is_free(qi, qj, self.config.resolution) {
            return false;
        }
        let length = (qj - qi).norm();
        self.graph.add_edge(a, b, length);
        self.components.union(i, j);
        true
    }

    /// Connects node `i` to its `k` nearest nodes (6.4.2).
    fn connect(&mut self, i: usize) {
        let near = self.tree.nearest(
            self.nodes[i].as_slice(),
            self.config.neighbours.saturating_add(1),
        );
        for (_, j) in near {
            self.try_edge(i, j);
        }
    }

    fn uniform_sample(&mut self) -> JointVector<A> {
        let dim = self.checker.arm().dim();
        let rng = &mut self.rng;
        let ranges = &self.ranges;
        JointVector::<A>::from_fn_generic(dim, U1, |j, _| {
            let [lo, hi] = ranges[j];
            rng.random_range(lo..=hi)
        })
    }

    fn sample_near(&mut self, node: usize) -> JointVector<A> {
        let radius = self.config.resample_radius;
        let dim = self.checker.arm().dim();
        let rng = &mut self.rng;
        let ranges = &self.ranges;
        let centre = &self.nodes[node];
        JointVector::<A>::from_fn_generic(dim, U1, |j, _| {
            let [lo, hi] = ranges[j];
            (centre[j] + rng.random_range(-radius..=radius)).clamp(lo, hi)
        })
    }

    /// Counts a sample; true when it is free.
    fn accept(&mut self, q: &JointVector<A>) -> bool {
        self.stats.samples += 1;
        let free = self.checker.is_free(q, self.margin);
        if !free {
            self.stats.rejected_samples += 1;
        }
        free
    }

    /// Samples the initial nodes (6.4.1) and connects them (6.4.2), unless the roadmap
    /// already has nodes.
    pub fn build(&mut self) {
        let started = Instant::now();
        let checks = self.checker.checks();
        self.deadline = self.deadline_from(started);
        if self.nodes.is_empty() {
            while self.nodes.len() < self.config.initial_nodes && self.out_of_budget().is_none() {
                let q = self.uniform_sample();
                if self.accept(&q) {
                    self.add_node(q);
                }
            }
            for i in 0..self.nodes.len() {
                self.connect(i);
            }
        }
        self.stats.collision_checks += self.checker.checks() - checks;
        self.stats.time += started.elapsed();
    }

    /// One enhancement round (6.4.3): connect the smaller components to the largest, then
    /// add `enhancement_nodes` nodes, mostly around nodes with few neighbours.
    pub fn enhance(&mut self) {
        let started = Instant::now();
        let checks = self.checker.checks();
        self.stats.enhancement_rounds += 1;
        self.connect_components();
        let sparse: Vec<usize> = (0..self.nodes.len())
            .filter(|&i| self.graph.edges(NodeIndex::new(i)).count() < self.config.few_neighbours)
            .collect();
        let mut added = 0;
        while added < self.config.enhancement_nodes && self.out_of_budget().is_none() {
            let q = if !sparse.is_empty() && self.rng.random_bool(0.7) {
                let node = sparse[self.rng.random_range(0..sparse.len())];
                self.sample_near(node)
            } else {
                self.uniform_sample()
            };
            if self.accept(&q) {
                let i = self.add_node(q);
                self.connect(i);
                added += 1;
            }
        }
        self.stats.collision_checks += self.checker.checks() - checks;
        self.stats.time += started.elapsed();
    }

    /// Tries to join every smaller component to the largest through its closest node pairs.
    fn connect_components(&mut self) {
        let labels = self.component_labels();
        let mut sizes = std::collections::BTreeMap::<usize, usize>::new();
        for &l in &labels {
            *sizes.entry(l).or_default() += 1;
        }
        // The largest component; ties go to the smallest label, for reproducibility.
        let Some((&largest, _)) = sizes.iter().max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
        else {
            return;
        };
        let probe = self.config.neighbours.saturating_mul(4);
        for (&component, _) in sizes.iter().filter(|(l, _)| **l != largest) {
            // First towards the largest component; failing that, towards the nearest other
            // one, so that pieces of a narrow passage join up into a chain.
            for towards_largest in [true, false] {
                let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
                for (node, _) in labels.iter().enumerate().filter(|(_, l)| **l == component) {
                    let near = self.tree.nearest(self.nodes[node].as_slice(), probe);
                    let own = self.components.find(node);
                    let target = self.components.find(largest);
                    if let Some(&(d, other)) = near.iter().find(|(_, j)| {
                        let theirs = self.components.find(*j);
                        if towards_largest {
                            theirs == target
                        } else {
                            theirs != own
                        }
                    }) {
                        pairs.push((d, node, other));
                    }
                }
                pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                let joined = pairs
                    .iter()
                    .take(self.config.connect_attempts)
                    .any(|&(_, node, other)| self.try_edge(node, other));
                if joined {
                    break;
                }
            }
        }
    }

    /// The node at `q`, added and connected if the roadmap has none there.
    fn insert(&mut self, q: &JointVector<A>) -> usize {
        if let Some(&(d, i)) = self.tree.nearest(q.as_slice(), 1).first()
            && d == 0.0
            && self.nodes[i] == *q
        {
            return i;
        }
        let i = self.add_node(q.clone());
        self.connect(i);
        i
    }

    /// Finds a path from `start` to `goal`: builds the roadmap if it is empty, joins start
    /// and goal to it, enhances it while they are in different components and the budget
    /// allows, then searches it with A* and smooths the result (6.4.4).
    ///
    /// Errors: a start or goal outside the joint ranges or not free;
    /// [`PlanError::NoPath`] when a budget runs out first.
    pub fn query(
        &mut self,
        start: &JointVector<A>,
        goal: &JointVector<A>,
    ) -> Result<PrmPath<JointVector<A>>, PlanError> {
        for (which, q) in [("start", start), ("goal", goal)] {
            let bad = |reason| PlanError::InvalidConfiguration { which, reason };
            self.checker
                .check_configuration(q.as_slice())
                .map_err(bad)?;
            if !self.checker.is_free(q, self.margin) {
                return Err(bad(format!(
                    "the arm is within the safety margin {:.4} of an obstacle",
                    self.margin
                )));
            }
        }
        self.build();
        let started = Instant::now();
        let checks = self.checker.checks();
        self.deadline = self.deadline_from(started);
        let s = self.insert(start);
        let g = self.insert(goal);
        self.stats.collision_checks += self.checker.checks() - checks;
        self.stats.time += started.elapsed();
        while !self.components.equiv(s, g) {
            if let Some(reason) = self.out_of_budget() {
                let stats = self.stats();
                return Err(PlanError::NoPath {
                    nodes: stats.nodes,
                    components: stats.components,
                    reason,
                });
            }
            self.enhance();
        }
        let started = Instant::now();
        let checks = self.checker.checks();
        let nodes = &self.nodes;
        let (roadmap_length, route) = petgraph::algo::astar(
            &self.graph,
            NodeIndex::new(s),
            |n| n.index() == g,
            |e| *e.weight(),
            |n| (&nodes[n.index()] - &nodes[g]).norm(),
        )
        .ok_or_else(|| PlanError::NoPath {
            nodes: self.nodes.len(),
            components: self.stats().components,
            reason: "A* found no route between nodes of one component".into(),
        })?;
        let waypoints: Vec<JointVector<A>> = route
            .iter()
            .map(|n| self.nodes[n.index()].clone())
            .collect();
        let (waypoints, shortcuts) = self.smooth(waypoints);
        self.stats.collision_checks += self.checker.checks() - checks;
        self.stats.time += started.elapsed();
        Ok(PrmPath {
            length: path_length(&waypoints),
            waypoints,
            roadmap_length,
            shortcuts,
            stats: self.stats(),
        })
    }

    /// Random shortcutting (6.4.4).
    fn smooth(&mut self, mut path: Vec<JointVector<A>>) -> (Vec<JointVector<A>>, usize) {
        let mut failures = 0;
        let mut shortcuts = 0;
        // A cap on all tries, since every success restarts the count of failures.
        let mut tries = 0;
        while failures < self.config.shortcut_attempts
            && tries < 20 * self.config.shortcut_attempts
            && path.len() > 2
        {
            tries += 1;
            let mut cumulative = Vec::with_capacity(path.len());
            let mut total = 0.0;
            cumulative.push(0.0);
            for w in path.windows(2) {
                total += (&w[1] - &w[0]).norm();
                cumulative.push(total);
            }
            let (mut s1, mut s2) = (
                self.rng.random_range(0.0..=total),
                self.rng.random_range(0.0..=total),
            );
            if s1 > s2 {
                core::mem::swap(&mut s1, &mut s2);
            }
            let segment = |s: f64| {
                cumulative
                    .partition_point(|&c| c <= s)
                    .clamp(1, path.len() - 1)
                    - 1
            };
            let (i, j) = (segment(s1), segment(s2));
            if i == j {
                failures += 1;
                continue;
            }
            let at = |k: usize, s: f64| {
                let span = cumulative[k + 1] - cumulative[k];
                let t = if span > 0.0 {
                    ((s - cumulative[k]) / span).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                path[k].lerp(&path[k + 1], t)
            };
            let (p1, p2) = (at(i, s1), at(j, s2));
            // Only a saving of at least 0.1 % of the length is "significant progress".
            let saving = (s2 - s1) - (&p2 - &p1).norm();
            if saving < 1e-3 * total
                || !self
                    .checker
                    .motion_is_free(&p1, &p2, self.config.resolution)
            {
                failures += 1;
                continue;
            }
            let mut shorter = Vec::with_capacity(path.len() + 2);
            shorter.extend_from_slice(&path[..=i]);
            shorter.push(p1);
            shorter.push(p2);
            shorter.extend_from_slice(&path[j + 1..]);
            shorter.dedup();
            path = shorter;
            shortcuts += 1;
            failures = 0;
        }
        // Shortcuts leave pairs of waypoints inside former segments; drop every waypoint
        // whose neighbours see each other directly.
        let mut k = 1;
        while k + 1 < path.len() {
            if self
                .checker
                .motion_is_free(&path[k - 1], &path[k + 1], self.config.resolution)
            {
                path.remove(k);
            } else {
                k += 1;
            }
        }
        (path, shortcuts)
    }
}

/// The joint-space length of the polyline through `path`.
pub fn path_length<D: nalgebra::Dim>(path: &[nalgebra::OVector<f64, D>]) -> f64
where
    DefaultAllocator: nalgebra::allocator::Allocator<D>,
{
    path.windows(2).map(|w| (&w[1] - &w[0]).norm()).sum()
}

#[cfg(test)]
mod tests {
    use super::NodeTree;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The scan (more joints than the kd-trees have) finds what a kd-tree finds: the same
    /// nodes in the same order, equal distances in node order, for every dimension a kd-tree
    /// has, with points repeated and on a coarse grid (many equal distances).
    #[test]
    fn the_scan_finds_the_kd_trees_neighbours() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for dim in 1..=8 {
            let mut tree = NodeTree::new(dim);
            let mut scan = NodeTree::scan(dim);
            let mut points: Vec<Vec<f64>> = Vec::new();
            for i in 0..400 {
                let q: Vec<f64> = if i % 7 == 3 {
                    points[rng.random_range(0..points.len())].clone()
                } else {
                    (0..dim)
                        .map(|_| f64::from(rng.random_range(-4..=4)) * 0.5)
                        .collect()
                };
                // The roadmap keeps twins out of the kd-tree (it holds 32 items at one point).
                if tree.nearest(&q, 1).first().is_none_or(|&(d, _)| d > 0.0) {
                    tree.add(&q, i);
                    scan.add(&q, i);
                }
                points.push(q);
            }
            for k in 0..100 {
                // Half the queries on the grid: many nodes at equal distances.
                let q: Vec<f64> = (0..dim)
                    .map(|_| match k % 2 {
                        0 => rng.random_range(-2.5..2.5),
                        _ => f64::from(rng.random_range(-5..=5)) * 0.5,
                    })
                    .collect();
                for n in [0, 1, 2, 10, 1000] {
                    assert_eq!(tree.nearest(&q, n), scan.nearest(&q, n), "dim {dim}, n {n}");
                }
            }
            assert!(
                tree.items.is_empty(),
                "dim {dim}: the kd-tree held every point"
            );
        }
        assert!(NodeTree::new(9).kd.is_none());
    }

    /// Points a kd-tree cannot hold (more than a bucket's 32 at one point, the roadmap's
    /// twins, and more than 32 on one plane of equal coordinates, samples clamped to one
    /// joint limit) leave the answers unchanged: the points it refuses are scanned.
    #[test]
    fn points_the_kd_tree_refuses_leave_the_answers_unchanged() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        for (dim, twins) in [(1, true), (2, true), (3, false), (6, true), (6, false)] {
            let mut tree = NodeTree::new(dim);
            let mut scan = NodeTree::scan(dim);
            for i in 0..300 {
                let q: Vec<f64> = (0..dim)
                    .map(|j| match (twins, j) {
                        (true, _) if i % 3 == 0 => 0.25,
                        (false, 0) => 1.5,
                        _ => rng.random_range(-2.0..2.0),
                    })
                    .collect();
                tree.add(&q, i);
                scan.add(&q, i);
            }
            for _ in 0..50 {
                let q: Vec<f64> = (0..dim).map(|_| rng.random_range(-2.5..2.5)).collect();
                for n in [1, 2, 10, 40, 1000] {
                    assert_eq!(tree.nearest(&q, n), scan.nearest(&q, n), "dim {dim}, n {n}");
                }
            }
            let q = vec![0.25; dim];
            assert_eq!(
                tree.nearest(&q, 120),
                scan.nearest(&q, 120),
                "dim {dim}, twins"
            );
            // The tree refused some points, and holds the rest.
            assert!(!tree.items.is_empty() && tree.in_tree() >= 32, "dim {dim}");
        }
    }
}

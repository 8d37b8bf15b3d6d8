//! The expression DAG that generated code is emitted from.
//!
//! Every node is hash-consed: building `a * b` twice yields the same node, so common
//! subexpressions are shared by construction and each becomes one `let` when emitted.
//! The constructors fold constants and push negations outward (`a + (-b)` becomes
//! `a - b`, `(-a) * b` becomes `-(a * b)`), so no operation is spent on a sign that the
//! surrounding sum can absorb.
//!
//! [`E`] wraps a node handle and implements [`Ring`], so the one DH formula of the model
//! (`Link::dh_transform`) and generic algorithms such as Newton-Euler run on it unchanged.

use dhgen_description::Ring;
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// Index of a node in a [`Graph`].
pub type Id = u32;

/// A hash map with a fast hasher (foldhash's, with a fixed seed, so expansion is
/// deterministic), for the engine's keys: nodes, node ids and monomials. std's default SipHash
/// guards a map against keys chosen to collide, which these, built by the engine, are not; and
/// the proc macro runs unoptimised, where SipHash took about a third of the generator's
/// instructions (docs/experiments.md, "Expansion time").
pub(crate) type FastMap<K, V> = HashMap<K, V, foldhash::fast::FixedState>;

/// An input of a generated function.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Sym {
    /// cos of joint j's full angle (offset included).
    Cos(usize),
    /// sin of joint j's full angle.
    Sin(usize),
    /// Full displacement of prismatic joint j (offset included).
    Len(usize),
    /// Joint velocity j.
    Qd(usize),
    /// Joint acceleration j.
    Qdd(usize),
    /// Parameter k of a payload held by the tool (`m, m·c, I about the tool origin`, the
    /// order of `dhgen::parameters::BODY_PARAMETER_NAMES`).
    Payload(usize),
}

/// One operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant (its bit pattern, so nodes can be hashed).
    Const(u64),
    /// An input.
    Sym(Sym),
    /// a + b
    Add(Id, Id),
    /// a - b
    Sub(Id, Id),
    /// a * b
    Mul(Id, Id),
    /// -a
    Neg(Id),
}

/// Exact comparison with a structural constant (0, 1 or −1), written as a function so the
/// intent (an exact identity, not a tolerance) is explicit.
fn is(x: f64, k: f64) -> bool {
    x == k
}

/// The node arena with its hash-consing index.
#[derive(Default, Debug)]
pub struct Graph {
    nodes: Vec<Node>,
    index: FastMap<Node, Id>,
}

impl Graph {
    /// The nodes in creation order (children before parents).
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The node with id `id`.
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id as usize]
    }

    fn intern(&mut self, node: Node) -> Id {
        let next = self.nodes.len() as Id;
        let id = *self.index.entry(node).or_insert(next);
        if id == next {
            self.nodes.push(node);
        }
        id
    }

    fn constant(&self, id: Id) -> Option<f64> {
        match self.nodes[id as usize] {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    fn negated(&self, id: Id) -> Option<Id> {
        match self.nodes[id as usize] {
            Node::Neg(a) => Some(a),
            _ => None,
        }
    }

    /// `(l, x)` where node `id` is the product `l · x` of a constant and a non-constant.
    fn scaled(&self, id: Id) -> Option<(f64, Id)> {
        match self.nodes[id as usize] {
            Node::Mul(a, b) => match (self.constant(a), self.constant(b)) {
                (Some(l), None) => Some((l, b)),
                (None, Some(l)) => Some((l, a)),
                _ => None,
            },
            _ => None,
        }
    }

    /// The constant `x` (negative zero is normalised to zero).
    pub fn konst(&mut self, x: f64) -> Id {
        let x = if x == 0.0 { 0.0 } else { x };
        self.intern(Node::Const(x.to_bits()))
    }

    /// An input symbol.
    pub fn sym(&mut self, s: Sym) -> Id {
        self.intern(Node::Sym(s))
    }

    /// `-a`
    pub fn neg(&mut self, a: Id) -> Id {
        if let Some(x) = self.constant(a) {
            return self.konst(-x);
        }
        if let Some(inner) = self.negated(a) {
            return inner;
        }
        if let Node::Sub(x, y) = self.nodes[a as usize] {
            return self.intern(Node::Sub(y, x));
        }
        self.intern(Node::Neg(a))
    }

    /// `a + b`
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => return self.konst(x + y),
            (Some(x), _) if is(x, 0.0) => return b,
            (_, Some(y)) if is(y, 0.0) => return a,
            _ => {}
        }
        match (self.negated(a), self.negated(b)) {
            (Some(x), Some(y)) => {
                let s = self.add(x, y);
                self.neg(s)
            }
            (None, Some(y)) => self.sub(a, y),
            (Some(x), None) => self.sub(b, x),
            (None, None) => self.intern(Node::Add(a.min(b), a.max(b))),
        }
    }

    /// `a - b`
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return self.konst(0.0);
        }
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => return self.konst(x - y),
            (Some(x), _) if is(x, 0.0) => return self.neg(b),
            (_, Some(y)) if is(y, 0.0) => return a,
            _ => {}
        }
        match (self.negated(a), self.negated(b)) {
            (_, Some(y)) => self.add(a, y),
            (Some(x), None) => {
                let s = self.add(x, b);
                self.neg(s)
            }
            (None, None) => self.intern(Node::Sub(a, b)),
        }
    }

    /// `a * b`
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => return self.konst(x * y),
            (Some(k), _) | (_, Some(k)) if is(k, 0.0) => return self.konst(0.0),
            (Some(k), _) if is(k, 1.0) => return b,
            (_, Some(k)) if is(k, 1.0) => return a,
            (Some(k), _) if is(k, -1.0) => return self.neg(b),
            (_, Some(k)) if is(k, -1.0) => return self.neg(a),
            (Some(k), _) if k < 0.0 => {
                let pk = self.konst(-k);
                let m = self.mul(pk, b);
                return self.neg(m);
            }
            (_, Some(k)) if k < 0.0 => {
                let pk = self.konst(-k);
                let m = self.mul(a, pk);
                return self.neg(m);
            }
            _ => {}
        }
        // k · (l · x) = (k·l) · x: one multiplication, not two.
        for (k, other) in [(a, b), (b, a)] {
            if let (Some(k), Some((l, x))) = (self.constant(k), self.scaled(other)) {
                let kl = self.konst(k * l);
                return self.mul(kl, x);
            }
        }
        match (self.negated(a), self.negated(b)) {
            (Some(x), Some(y)) => self.mul(x, y),
            (Some(x), None) => {
                let m = self.mul(x, b);
                self.neg(m)
            }
            (None, Some(y)) => {
                let m = self.mul(a, y);
                self.neg(m)
            }
            (None, None) => self.intern(Node::Mul(a.min(b), a.max(b))),
        }
    }
}

/// A shared, growable graph.
pub type SharedGraph = Rc<RefCell<Graph>>;

/// An expression: a constant not yet placed in a graph, or a node of one.
///
/// Keeping constants outside the graph until they meet a node lets constant arithmetic
/// (products of DH parameters, masses, lengths) fold to one number at generation time.
#[derive(Clone, Debug)]
pub enum E {
    /// A constant.
    K(f64),
    /// A node of a graph.
    N(SharedGraph, Id),
}

impl E {
    /// A graph input.
    pub fn sym(g: &SharedGraph, s: Sym) -> E {
        let id = g.borrow_mut().sym(s);
        E::N(g.clone(), id)
    }

    /// The node id in `g` (constants are placed in `g` first).
    pub fn id_in(&self, g: &SharedGraph) -> Id {
        match self {
            E::K(x) => g.borrow_mut().konst(*x),
            E::N(_, id) => *id,
        }
    }
}

fn binary(a: E, b: E, fold: fn(f64, f64) -> f64, op: fn(&mut Graph, Id, Id) -> Id) -> E {
    match (&a, &b) {
        (E::K(x), E::K(y)) => E::K(fold(*x, *y)),
        (E::N(g, _), _) | (_, E::N(g, _)) => {
            let g = g.clone();
            let (ia, ib) = (a.id_in(&g), b.id_in(&g));
            let r = op(&mut g.borrow_mut(), ia, ib);
            // A result that folded to a constant leaves the graph again.
            match g.borrow().constant(r) {
                Some(x) => E::K(x),
                None => E::N(g.clone(), r),
            }
        }
    }
}

impl core::ops::Add for E {
    type Output = E;
    fn add(self, rhs: E) -> E {
        binary(self, rhs, |a, b| a + b, Graph::add)
    }
}

impl core::ops::Sub for E {
    type Output = E;
    fn sub(self, rhs: E) -> E {
        binary(self, rhs, |a, b| a - b, Graph::sub)
    }
}

impl core::ops::Mul for E {
    type Output = E;
    fn mul(self, rhs: E) -> E {
        binary(self, rhs, |a, b| a * b, Graph::mul)
    }
}

impl core::ops::Neg for E {
    type Output = E;
    fn neg(self) -> E {
        match self {
            E::K(x) => E::K(-x),
            E::N(g, id) => {
                let r = g.borrow_mut().neg(id);
                E::N(g, r)
            }
        }
    }
}

impl Ring for E {
    fn from_f64(x: f64) -> E {
        E::K(x)
    }
}

/// Operation counts of a set of outputs (each shared node counted once).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions, subtractions and negations.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Square roots.
    pub sqrt: usize,
    /// `sin_cos` evaluations (one per revolute joint read), done once per configuration.
    pub sincos: usize,
}

impl OpCount {
    /// All arithmetic operations (`sin_cos` not included).
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.sqrt
    }
}

impl core::ops::AddAssign for OpCount {
    fn add_assign(&mut self, o: OpCount) {
        self.add += o.add;
        self.mul += o.mul;
        self.div += o.div;
        self.sqrt += o.sqrt;
        self.sincos += o.sincos;
    }
}

/// The nodes reachable from `roots`, in creation (= dependency) order.
pub fn reachable(g: &Graph, roots: impl IntoIterator<Item = Id>) -> Vec<Id> {
    let mut seen = vec![false; g.nodes.len()];
    let mut stack: Vec<Id> = roots.into_iter().collect();
    while let Some(id) = stack.pop() {
        if std::mem::replace(&mut seen[id as usize], true) {
            continue;
        }
        match g.nodes[id as usize] {
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => {
                stack.push(a);
                stack.push(b);
            }
            Node::Neg(a) => stack.push(a),
            Node::Const(_) | Node::Sym(_) => {}
        }
    }
    (0..g.nodes.len() as Id)
        .filter(|&i| seen[i as usize])
        .collect()
}

/// The tangent of joint j's variable for [`derivative`]: `d cos θ_j = −sin θ_j`,
/// `d sin θ_j = cos θ_j` (revolute) or `d d_j = 1` (prismatic), every other input's 0.
pub fn joint_tangent(graph: &SharedGraph, j: usize) -> impl Fn(Sym) -> E + '_ {
    move |s| match s {
        Sym::Cos(i) if i == j => -E::sym(graph, Sym::Sin(j)),
        Sym::Sin(i) if i == j => E::sym(graph, Sym::Cos(j)),
        Sym::Len(i) if i == j => E::K(1.0),
        _ => E::K(0.0),
    }
}

/// The derivatives of the expressions `roots` of `graph` along the tangent that gives each
/// input symbol the derivative `tangent(s)`: forward mode over the graph, every node's
/// derivative built once, in `graph` (so it shares what the values, and other derivatives
/// built in the same graph, already compute).
pub fn derivative(graph: &SharedGraph, roots: &[E], tangent: impl Fn(Sym) -> E) -> Vec<E> {
    let ids: Vec<Id> = roots.iter().map(|e| e.id_in(graph)).collect();
    let order = reachable(&graph.borrow(), ids.iter().copied());
    let mut d: FastMap<Id, E> = FastMap::with_capacity_and_hasher(order.len(), Default::default());
    for id in order {
        let node = graph.borrow().node(id);
        let value = |x: Id| E::N(graph.clone(), x);
        let dx = |x: Id| d[&x].clone();
        let t = match node {
            Node::Const(_) => E::K(0.0),
            Node::Sym(s) => tangent(s),
            Node::Neg(a) => -dx(a),
            Node::Add(a, b) => dx(a) + dx(b),
            Node::Sub(a, b) => dx(a) - dx(b),
            Node::Mul(a, b) => dx(a) * value(b) + value(a) * dx(b),
        };
        d.insert(id, t);
    }
    ids.iter().map(|id| d[id].clone()).collect()
}

/// The expressions `roots` of `graph` with input symbols replaced where `value` gives one
/// (constants fold as the expressions are rebuilt, in `graph`, each node once).
pub fn substitute(graph: &SharedGraph, roots: &[E], value: impl Fn(Sym) -> Option<E>) -> Vec<E> {
    let ids: Vec<Option<Id>> = roots
        .iter()
        .map(|e| match e {
            E::K(_) => None,
            E::N(_, id) => Some(*id),
        })
        .collect();
    let order = reachable(&graph.borrow(), ids.iter().flatten().copied());
    let mut v: FastMap<Id, E> = FastMap::with_capacity_and_hasher(order.len(), Default::default());
    for id in order {
        let node = graph.borrow().node(id);
        let x = |a: Id| v[&a].clone();
        let e = match node {
            Node::Const(c) => E::K(f64::from_bits(c)),
            Node::Sym(s) => value(s).unwrap_or_else(|| E::N(graph.clone(), id)),
            Node::Neg(a) => -x(a),
            Node::Add(a, b) => x(a) + x(b),
            Node::Sub(a, b) => x(a) - x(b),
            Node::Mul(a, b) => x(a) * x(b),
        };
        v.insert(id, e);
    }
    roots
        .iter()
        .zip(&ids)
        .map(|(e, id)| id.map_or_else(|| e.clone(), |id| v[&id].clone()))
        .collect()
}

/// All arithmetic operations needed to evaluate the expressions `outs` of `graph`, shared
/// nodes counted once: what derivations are compared by.
pub fn cost<'a>(graph: &SharedGraph, outs: impl IntoIterator<Item = &'a E>) -> usize {
    let roots: Vec<Id> = outs.into_iter().map(|e| e.id_in(graph)).collect();
    count(&graph.borrow(), roots).total()
}

/// Counts the operations needed to evaluate `roots`, sharing common nodes.
pub fn count(g: &Graph, roots: impl IntoIterator<Item = Id>) -> OpCount {
    let mut c = OpCount::default();
    for id in reachable(g, roots) {
        match g.nodes[id as usize] {
            Node::Add(..) | Node::Sub(..) | Node::Neg(..) => c.add += 1,
            Node::Mul(..) => c.mul += 1,
            Node::Const(_) | Node::Sym(_) => {}
        }
    }
    c
}

//! Emission: expressions become straight-line Rust, one immutable `let` per shared node.
//!
//! rustc's debug-info generation overflows its stack on functions with a few thousand
//! `let`s (the Panda's ∂τ whole, about 3,380, with rustc 1.89 and 1.95, in debug builds and in
//! optimised ones with debug information), and release compile time grows superlinearly with
//! function size, so the outputs of one quantity of more than [`WHOLE_STATEMENTS`] statements
//! are split into parts of at most [`MAX_STATEMENTS`] statements, each its own function writing
//! into the caller's output.

use crate::graph::{E, Id, Node, OpCount, SharedGraph, Sym, count};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

/// The most statements one part of a split function may hold, as estimated while cutting
/// (operations and stores, and two loads per operation: about 300 operations).
pub const MAX_STATEMENTS: usize = 900;

/// The most statements (operations, stores and loads, each counted once) of a function
/// emitted whole, in one part. Above, it is cut into parts of [`MAX_STATEMENTS`]: each value
/// crossing a cut is stored and loaded again, which costs more than the register pressure of
/// one longer function up to this size, and less beyond (raising the bound from 1,300 took
/// the Panda's C from 4,170 to 3,896 instructions per call). The bound also caps the `let`s of
/// one function, which keeps debug builds from crashing (module documentation). The
/// measurements: docs/experiments.md, "Derivatives of the dynamics against Pinocchio".
pub const WHOLE_STATEMENTS: usize = 2_000;

/// One output: where to store it (an lvalue) and its expression.
pub struct Output {
    /// The lvalue, e.g. `out[(0, 1)]`.
    pub target: TokenStream,
    /// The value.
    pub value: E,
}

/// Straight-line code for a set of outputs, in parts.
pub struct Emitted {
    /// Statement lists, each at most [`MAX_STATEMENTS`] long.
    pub parts: Vec<Vec<TokenStream>>,
    /// Operations in the emitted code.
    pub ops: OpCount,
    /// Values passed between parts.
    pub scratch: usize,
    /// Which joints' variables (cos/sin or displacement) the code reads.
    pub joints: Vec<usize>,
    /// Per part, the argument arrays it reads (`"qd"`, `"qdd"`, `"tau"`).
    pub part_inputs: Vec<Vec<&'static str>>,
    /// Per part, whether it stores outputs and whether it touches the scratch array.
    pub part_uses: Vec<PartUse>,
    /// The first part of the late stage ([`emit_staged`]); `parts.len()` for [`emit`].
    pub late_part: usize,
}

/// What one part of a split function touches besides its inputs.
#[derive(Clone, Copy, Debug, Default)]
pub struct PartUse {
    /// It stores at least one output.
    pub out: bool,
    /// It reads or writes the scratch array.
    pub scratch: bool,
}

fn ident(s: &str) -> Ident {
    Ident::new(s, Span::call_site())
}

/// The name and the load of an input symbol.
fn sym_load(s: Sym) -> (Ident, TokenStream) {
    let (name, load) = match s {
        Sym::Cos(j) => (format!("c{}", j + 1), quote!(self.c[#j])),
        Sym::Sin(j) => (format!("s{}", j + 1), quote!(self.s[#j])),
        Sym::Len(j) => (format!("d{}", j + 1), quote!(self.d[#j])),
        Sym::Qd(j) => (format!("qd{}", j + 1), quote!(qd[#j])),
        Sym::Qdd(j) => (format!("qdd{}", j + 1), quote!(qdd[#j])),
        Sym::Payload(k) => (format!("pl{k}"), quote!(payload[#k])),
    };
    (ident(&name), load)
}

/// The argument array an input symbol loads from (`"qd"`, `"qdd"`, `"tau"`, `"payload"`);
/// `None` for the joint variables, which the `State` holds.
pub fn input_array(s: Sym) -> Option<&'static str> {
    match s {
        Sym::Qd(_) => Some("qd"),
        Sym::Qdd(_) => Some("qdd"),
        Sym::Payload(_) => Some("payload"),
        Sym::Cos(_) | Sym::Sin(_) | Sym::Len(_) => None,
    }
}

/// `x` as an `f64` expression: a literal, or for a non-finite value (which
/// [`limits::check`](crate::limits::check) keeps out of generated code, and which
/// `Literal::f64_suffixed` would panic on) the named constant.
pub fn float(x: f64) -> TokenStream {
    if x.is_finite() {
        let lit = Literal::f64_suffixed(x);
        quote!(#lit)
    } else if x.is_nan() {
        quote!(::core::f64::NAN)
    } else if x > 0.0 {
        quote!(::core::f64::INFINITY)
    } else {
        quote!(::core::f64::NEG_INFINITY)
    }
}

/// A numeric constant converted to the scalar type `T`.
pub fn constant(x: f64) -> TokenStream {
    let lit = float(x);
    quote!(::dhgen::__private::nalgebra::convert::<f64, T>(#lit))
}

/// Emits the outputs; constants that are outputs are stored directly.
///
/// A function of more than [`WHOLE_STATEMENTS`] statements is cut, in dependency order, into
/// parts of at most [`MAX_STATEMENTS`] statements, each cut where few values cross it. A value
/// that a later part needs is passed through a scratch array (`w[slot]`), so every node is
/// computed exactly once however the function is split.
pub fn emit(graph: &SharedGraph, outputs: Vec<Output>) -> Emitted {
    emit_staged(graph, outputs, None)
}

/// [`emit`] in two stages when `late` is given: the outputs that do not read a symbol for
/// which `late` holds, with everything they need, in parts `..late_part`; the rest in parts
/// `late_part..` (at least one part each, possibly empty). Between the two, the caller may
/// compute the late symbols from the early outputs (the bias torques from ∂τ/∂q̇, then q̈,
/// before ∂τ/∂q at that q̈). Constant outputs are stored in part 0, with the early ones.
pub fn emit_staged(
    graph: &SharedGraph,
    outputs: Vec<Output>,
    late: Option<&dyn Fn(Sym) -> bool>,
) -> Emitted {
    let graph = graph.borrow();
    let size = graph.nodes().len();
    let ids: Vec<Option<Id>> = outputs
        .iter()
        .map(|o| match &o.value {
            E::K(_) => None,
            E::N(_, id) => Some(*id),
        })
        .collect();
    // Per node, whether it reads a late symbol: operands have smaller ids than the operations
    // reading them, so one pass in id order settles it.
    let mut reads_late = vec![false; size];
    if let Some(late) = late {
        for id in 0..size {
            let node = graph.node(id as Id);
            reads_late[id] = match node {
                Node::Sym(s) => late(s),
                _ => children(node).iter().any(|&c| reads_late[c as usize]),
            };
        }
    }
    let is_late = |id: &Option<Id>| id.is_some_and(|id| reads_late[id as usize]);
    let early_roots: Vec<Id> = ids
        .iter()
        .filter(|i| !is_late(i))
        .flatten()
        .copied()
        .collect();
    let early_count = postorder(&graph, early_roots.iter().copied()).len();
    let order = postorder(
        &graph,
        early_roots
            .into_iter()
            .chain(ids.iter().filter(|i| is_late(i)).flatten().copied()),
    );
    let ops = count(&graph, ids.iter().flatten().copied());
    let is_op = |id: Id| !matches!(graph.node(id), Node::Sym(_) | Node::Const(_));
    // Per node, dense by id: the outputs its part stores, its part, the last later part that
    // reads it, its scratch slot (NONE where there is none).
    const NONE: u32 = u32::MAX;
    let mut stored_at: Vec<Vec<usize>> = vec![Vec::new(); size];
    for (i, id) in ids.iter().enumerate() {
        if let Some(id) = id {
            stored_at[*id as usize].push(i);
        }
    }
    // A function that fits in [`WHOLE_STATEMENTS`] (each operation, store and load counted
    // once) stays whole; a larger one is cut into parts by statement budget (operations +
    // stores + values read from earlier parts, estimated generously by the operands).
    let whole: usize = order
        .iter()
        .map(|&id| {
            if is_op(id) {
                1 + stored_at[id as usize].len()
            } else {
                1
            }
        })
        .sum();
    let cost = |id: Id| {
        if is_op(id) {
            1 + stored_at[id as usize].len() + 2
        } else {
            0
        }
    };
    let cuts = if whole <= WHOLE_STATEMENTS {
        vec![false; order.len()]
    } else {
        cuts(&graph, &order, early_count, &cost, &is_op)
    };
    let mut part_of = vec![NONE; size];
    let mut parts_nodes: Vec<Vec<Id>> = vec![Vec::new()];
    let mut late_part = None;
    for (i, &id) in order.iter().enumerate() {
        if late.is_some() && i >= early_count && late_part.is_none() {
            parts_nodes.push(Vec::new());
            late_part = Some(parts_nodes.len() - 1);
        }
        if is_op(id) {
            part_of[id as usize] = (parts_nodes.len() - 1) as u32;
            parts_nodes.last_mut().expect("non-empty").push(id);
        }
        if cuts[i] && !parts_nodes.last().expect("non-empty").is_empty() {
            parts_nodes.push(Vec::new());
        }
    }
    if late.is_some() && late_part.is_none() {
        parts_nodes.push(Vec::new());
    }
    let late_part = late_part.unwrap_or(parts_nodes.len() - usize::from(late.is_some()));
    // The part storing an output that is a bare symbol: the first of its stage.
    let bare_part = |id: Id| {
        if reads_late[id as usize] {
            late_part
        } else {
            0
        }
    };
    // Values crossing parts get scratch slots, reused once their last reader has run (like
    // registers), so the array stays as small as the most values alive between two parts.
    let mut last_use = vec![NONE; size];
    for &id in &order {
        if !is_op(id) {
            continue;
        }
        for child in children(graph.node(id)) {
            let c = child as usize;
            if is_op(child) && part_of[c] != part_of[id as usize] {
                let here = part_of[id as usize];
                last_use[c] = if last_use[c] == NONE {
                    here
                } else {
                    last_use[c].max(here)
                };
            }
        }
    }
    let mut slot = vec![NONE; size];
    let mut free: Vec<usize> = Vec::new();
    let mut live: Vec<(usize, usize)> = Vec::new(); // (last part reading it, slot)
    let mut slots = 0usize;
    for (p, nodes) in parts_nodes.iter().enumerate() {
        live.retain(|&(last, k)| {
            if last < p {
                free.push(k);
                false
            } else {
                true
            }
        });
        for &id in nodes {
            let last = last_use[id as usize];
            if last != NONE {
                let k = free.pop().unwrap_or_else(|| {
                    slots += 1;
                    slots - 1
                });
                slot[id as usize] = k as u32;
                live.push((last as usize, k));
            }
        }
    }
    // A product read once, by a sum or difference in its own part, and neither stored nor
    // passed on, is fused into it: `Real::mul_add_fast`, one instruction where the target has
    // FMA, the same multiplication and addition (rounded alike) elsewhere. Not into a running
    // sum that is ready after the product's factors (by depth in the graph): a fused
    // multiply-add takes longer than an addition (4–5 cycles against 3 on AMD Zen), so fusing
    // there would lengthen the sum's chain (with every single-use product fused, Panda
    // C(q, q̇) took 14 % longer with AVX2 and FMA; with this rule 4 % less than unfused).
    let mut readers = vec![0u32; size];
    let mut depth = vec![0u32; size];
    for &id in &order {
        if is_op(id) {
            for child in children(graph.node(id)) {
                readers[child as usize] += 1;
                depth[id as usize] = depth[id as usize].max(depth[child as usize] + 1);
            }
        }
    }
    let fusible = |m: Id, into: Id, other: Id| {
        let Node::Mul(x, y) = graph.node(m) else {
            return false;
        };
        readers[m as usize] == 1
            && stored_at[m as usize].is_empty()
            && slot[m as usize] == NONE
            && part_of[m as usize] == part_of[into as usize]
            && !(matches!(graph.node(other), Node::Add(..) | Node::Sub(..))
                && depth[other as usize] > depth[x as usize].max(depth[y as usize]))
    };
    let mut fused = vec![false; size];
    for &id in &order {
        match graph.node(id) {
            Node::Add(a, b) | Node::Sub(a, b) => {
                if fusible(b, id, a) {
                    fused[b as usize] = true;
                } else if fusible(a, id, b) {
                    fused[a as usize] = true;
                }
            }
            _ => {}
        }
    }
    // Every value has one name wherever it is read: inputs by what they are, constants
    // `k<id>`, operations `t<id>`.
    let name = |id: Id| -> Ident {
        match graph.node(id) {
            Node::Sym(s) => sym_load(s).0,
            Node::Const(_) => ident(&format!("k{id}")),
            _ => ident(&format!("t{id}")),
        }
    };
    let mut parts = Vec::new();
    let mut part_inputs = Vec::new();
    let mut part_uses = Vec::new();
    for (p, nodes) in parts_nodes.iter().enumerate() {
        let mut uses = PartUse::default();
        let mut inputs: Vec<&'static str> = Vec::new();
        let mut stmts = Vec::new();
        // Inputs of this part: symbols, constants and values of earlier parts.
        let mut needed: Vec<Id> = nodes
            .iter()
            .flat_map(|&id| children(graph.node(id)))
            .filter(|c| !is_op(*c) || part_of[*c as usize] != p as u32)
            .collect();
        // Outputs that are bare symbols or constants have no operation of their own: the first
        // part of their stage loads and stores them.
        needed.extend(
            ids.iter()
                .flatten()
                .copied()
                .filter(|&id| !is_op(id) && bare_part(id) == p),
        );
        needed.sort_unstable();
        needed.dedup();
        // The joint variables' sines and cosines and the constants are loaded at the top; values
        // of earlier parts and the arguments (q̇, q̈, τ, payload) just before their first
        // reader, held in `loads` until then. Loaded at the top of a long part, they held
        // registers (or were spilled and reloaded) until read: Panda ∂τ 8,378 → 7,991
        // instructions on the default x86-64 target, 5,968 → 5,401 on x86-64-v3, a general
        // 8-joint arm's 9,907 → 8,873. Loading the sines, cosines and constants late too made
        // small functions longer (PUMA 560 τ +2 %).
        let mut loads: Vec<Option<TokenStream>> = vec![None; needed.len()];
        for (slot_of_load, &id) in loads.iter_mut().zip(&needed) {
            let load = match graph.node(id) {
                Node::Sym(sym) => {
                    if let Some(a) = input_array(sym).filter(|a| !inputs.contains(a)) {
                        inputs.push(a);
                    }
                    sym_load(sym).1
                }
                Node::Const(bits) => constant(f64::from_bits(bits)),
                _ => {
                    let k = slot[id as usize] as usize;
                    uses.scratch = true;
                    quote!(w[#k])
                }
            };
            let n = name(id);
            let stmt = quote!(let #n: T = #load;);
            let lazy = match graph.node(id) {
                Node::Sym(sym) => input_array(sym).is_some(),
                Node::Const(_) => false,
                _ => true,
            };
            if lazy {
                *slot_of_load = Some(stmt);
            } else {
                stmts.push(stmt);
            }
        }
        let mut load = |id: Id, stmts: &mut Vec<TokenStream>| {
            if let Some(s) = needed.binary_search(&id).ok().and_then(|i| loads[i].take()) {
                stmts.push(s);
            }
        };
        let factors = |m: Id| match graph.node(m) {
            Node::Mul(x, y) => (name(x), name(y)),
            _ => unreachable!("only products are fused"),
        };
        for &id in nodes {
            if fused[id as usize] {
                continue;
            }
            for c in children(graph.node(id)) {
                match graph.node(c) {
                    Node::Mul(x, y) if fused[c as usize] => {
                        load(x, &mut stmts);
                        load(y, &mut stmts);
                    }
                    _ => load(c, &mut stmts),
                }
            }
            let n = name(id);
            let rhs = match graph.node(id) {
                Node::Add(a, b) if fused[b as usize] || fused[a as usize] => {
                    let (m, c) = if fused[b as usize] { (b, a) } else { (a, b) };
                    let ((x, y), c) = (factors(m), name(c));
                    quote!(::dhgen::__private::Real::mul_add_fast(#x, #y, #c))
                }
                Node::Add(a, b) => {
                    let (a, b) = (name(a), name(b));
                    quote!(#a + #b)
                }
                // a − x·y = (−x)·y + a, and x·y − b = x·y + (−b): negation is exact.
                Node::Sub(a, b) if fused[b as usize] => {
                    let ((x, y), a) = (factors(b), name(a));
                    quote!(::dhgen::__private::Real::mul_add_fast(-#x, #y, #a))
                }
                Node::Sub(a, b) if fused[a as usize] => {
                    let ((x, y), b) = (factors(a), name(b));
                    quote!(::dhgen::__private::Real::mul_add_fast(#x, #y, -#b))
                }
                Node::Sub(a, b) => {
                    let (a, b) = (name(a), name(b));
                    quote!(#a - #b)
                }
                Node::Mul(a, b) => {
                    let (a, b) = (name(a), name(b));
                    quote!(#a * #b)
                }
                Node::Neg(a) => {
                    let a = name(a);
                    quote!(-#a)
                }
                Node::Sym(_) | Node::Const(_) => unreachable!("operations only"),
            };
            stmts.push(quote!(let #n: T = #rhs;));
            if slot[id as usize] != NONE {
                let k = slot[id as usize] as usize;
                uses.scratch = true;
                stmts.push(quote!(w[#k] = #n;));
            }
            for &i in &stored_at[id as usize] {
                let target = &outputs[i].target;
                uses.out = true;
                stmts.push(quote!(#target = #n;));
            }
        }
        for (i, o) in outputs.iter().enumerate() {
            let target = &o.target;
            match (&o.value, ids[i]) {
                (E::K(x), _) if p == 0 => {
                    let c = constant(*x);
                    uses.out = true;
                    stmts.push(quote!(#target = #c;));
                }
                (_, Some(id)) if !is_op(id) && bare_part(id) == p => {
                    load(id, &mut stmts);
                    let value = name(id);
                    uses.out = true;
                    stmts.push(quote!(#target = #value;));
                }
                _ => {}
            }
        }
        parts.push(stmts);
        part_inputs.push(inputs);
        part_uses.push(uses);
    }
    let mut joints: Vec<usize> = order
        .iter()
        .filter_map(|&id| match graph.node(id) {
            Node::Sym(Sym::Cos(j) | Sym::Sin(j) | Sym::Len(j)) => Some(j),
            _ => None,
        })
        .collect();
    joints.dedup();
    joints.sort_unstable();
    joints.dedup();
    Emitted {
        parts,
        ops,
        scratch: slots,
        joints,
        part_inputs,
        part_uses,
        late_part,
    }
}

/// Where to cut `order` into parts: `cuts[i]` when a part ends after `order[i]`. Each stage
/// (`..early_count`, then the rest) is cut on its own, every part costing at most
/// [`MAX_STATEMENTS`] (by `cost`); within the last quarter of each part's budget the cut goes
/// where the fewest values computed before it are read after it (each is stored to the
/// scratch array and loaded again).
fn cuts(
    graph: &crate::graph::Graph,
    order: &[Id],
    early_count: usize,
    cost: &dyn Fn(Id) -> usize,
    is_op: &dyn Fn(Id) -> bool,
) -> Vec<bool> {
    let len = order.len();
    let limit = MAX_STATEMENTS;
    let mut cuts = vec![false; len];
    // live[p]: the operations at positions ≤ p read at a position > p.
    let mut position = vec![usize::MAX; graph.nodes().len()];
    for (i, &id) in order.iter().enumerate() {
        position[id as usize] = i;
    }
    let mut last_read = vec![0usize; len];
    for (i, &id) in order.iter().enumerate() {
        for c in children(graph.node(id)) {
            if is_op(c) {
                let d = position[c as usize];
                last_read[d] = last_read[d].max(i);
            }
        }
    }
    let mut delta = vec![0i64; len + 1];
    for d in 0..len {
        if last_read[d] > d {
            delta[d] += 1;
            delta[last_read[d]] -= 1;
        }
    }
    let mut live = vec![0i64; len];
    let mut running = 0i64;
    for p in 0..len {
        running += delta[p];
        live[p] = running;
    }
    for (start, end) in [(0, early_count), (early_count, len)] {
        let mut s = start;
        loop {
            let mut total = 0usize;
            let mut last_fit = None;
            let mut window = None;
            for (i, &id) in order.iter().enumerate().take(end).skip(s) {
                total += cost(id);
                if total > limit {
                    break;
                }
                last_fit = Some(i);
                if window.is_none() && total * 4 >= limit * 3 {
                    window = Some(i);
                }
            }
            if total <= limit {
                break;
            }
            let Some(e) = last_fit else {
                // One node over budget (a store to many outputs): a part of its own.
                cuts[s] = s + 1 < end;
                s += 1;
                continue;
            };
            let w = window.unwrap_or(e);
            let p = (w..=e).rev().min_by_key(|&p| live[p]).expect("w ≤ e");
            cuts[p] = true;
            s = p + 1;
        }
    }
    cuts
}

fn children(node: Node) -> Vec<Id> {
    match node {
        Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => vec![a, b],
        Node::Neg(a) => vec![a],
        Node::Const(_) | Node::Sym(_) => vec![],
    }
}

/// The nodes needed by `roots`, each after its operands, visiting the roots in order and
/// each operand depth-first: a value is computed just before its first use, which keeps
/// live ranges (and register spills in the compiled code) short.
fn postorder(graph: &crate::graph::Graph, roots: impl IntoIterator<Item = Id>) -> Vec<Id> {
    let mut seen = vec![false; graph.nodes().len()];
    let mut out = Vec::new();
    for root in roots {
        // Iterative DFS: (node, operands pushed yet).
        let mut stack = vec![(root, false)];
        while let Some((id, expanded)) = stack.pop() {
            if seen[id as usize] {
                continue;
            }
            if expanded {
                seen[id as usize] = true;
                out.push(id);
            } else {
                stack.push((id, true));
                for c in children(graph.node(id)).into_iter().rev() {
                    if !seen[c as usize] {
                        stack.push((c, false));
                    }
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where each output is stored: the index of the part whose statements assign `target`.
    fn stored_in(emitted: &Emitted, target: &str) -> Vec<usize> {
        emitted
            .parts
            .iter()
            .enumerate()
            .filter(|(_, stmts)| {
                stmts.iter().any(|s| {
                    s.to_string()
                        .replace(' ', "")
                        .starts_with(&format!("{target}="))
                })
            })
            .map(|(p, _)| p)
            .collect()
    }

    #[test]
    fn a_long_function_is_cut_where_no_value_crosses() {
        // 40 independent chains of 60 operations each, too long to stay whole: cut where one
        // chain ends and the next begins, no value passes from part to part.
        let graph = SharedGraph::default();
        let (x, y) = (E::sym(&graph, Sym::Qd(0)), E::sym(&graph, Sym::Qd(1)));
        let outputs: Vec<Output> = (0..40)
            .map(|k| {
                let mut v = x.clone();
                for step in 0..30 {
                    v = v * E::K(2.0 + f64::from(k * 30 + step)) + y.clone();
                }
                Output {
                    target: format!("out[{k}]").parse().expect("an lvalue"),
                    value: v,
                }
            })
            .collect();
        let emitted = emit(&graph, outputs);
        assert_eq!(emitted.ops.total(), 40 * 60);
        assert!(emitted.parts.len() >= 8, "{} parts", emitted.parts.len());
        assert_eq!(emitted.scratch, 0);
    }

    #[test]
    fn staged_emission_computes_what_the_late_input_does_not_reach_first() {
        let graph = SharedGraph::default();
        let qd = E::sym(&graph, Sym::Qd(0));
        let qdd = E::sym(&graph, Sym::Qdd(0));
        let shared = qd.clone() * qd.clone() + qd.clone();
        let output = |name: &str, value: E| Output {
            target: name.parse().expect("an lvalue"),
            value,
        };
        // Late outputs first in the list, early ones after, a bare late symbol and a constant.
        let outputs = vec![
            output("out[0]", shared.clone() * qdd.clone()),
            output("out[1]", shared.clone() * shared.clone()),
            output("out[2]", qdd),
            output("out[3]", E::K(2.5)),
        ];
        let late = |s: Sym| matches!(s, Sym::Qdd(_));
        let emitted = emit_staged(&graph, outputs, Some(&late));
        let l = emitted.late_part;
        assert!(
            l >= 1 && l < emitted.parts.len(),
            "two stages: {l} of {}",
            emitted.parts.len()
        );
        // No early part reads q̈; the early output and the constant are stored before the late
        // stage, the outputs reading q̈ in it, each exactly once.
        assert!(emitted.part_inputs[..l].iter().all(|i| !i.contains(&"qdd")));
        assert_eq!(stored_in(&emitted, "out[1]"), vec![0]);
        assert_eq!(stored_in(&emitted, "out[3]"), vec![0]);
        assert_eq!(stored_in(&emitted, "out[0]"), vec![l]);
        assert_eq!(stored_in(&emitted, "out[2]"), vec![l]);
        // The value both stages need is computed once, in the early stage, and passed on.
        assert_eq!(emitted.ops.total(), 4);
        assert!(emitted.scratch >= 1);
        // Without a late input: one part, as `emit` makes it.
        let plain = emit(&graph, vec![output("out[0]", shared.clone() * shared)]);
        assert_eq!((plain.parts.len(), plain.late_part), (1, 1));
    }
}

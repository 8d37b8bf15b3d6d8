//! Emission: expressions become straight-line Rust, one immutable `let` per shared node.
//!
//! rustc's debug-info generation overflows its stack on functions with a few thousand
//! `let`s, and release compile time grows superlinearly with function size, so the outputs
//! of one quantity are split into parts of at most [`MAX_STATEMENTS`] statements, each
//! its own function writing into the caller's output.

use crate::graph::{E, Graph, Id, Node, OpCount, SharedGraph, Sym, count, reachable};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use std::collections::HashMap;

/// The most statements one generated function may hold.
pub const MAX_STATEMENTS: usize = 900;

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
    /// Operations in the emitted code (summed over parts).
    pub ops: OpCount,
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
        Sym::Tau(j) => (format!("tau{}", j + 1), quote!(tau[#j])),
    };
    (ident(&name), load)
}

/// A numeric constant converted to the scalar type `T`.
pub fn constant(x: f64) -> TokenStream {
    let lit = Literal::f64_suffixed(x);
    quote!(::dhgen::nalgebra::convert::<f64, T>(#lit))
}

/// Emits the outputs; constants that are outputs are stored directly.
pub fn emit(g: &SharedGraph, outputs: Vec<Output>) -> Emitted {
    let graph = g.borrow();
    let ids: Vec<Option<Id>> = outputs
        .iter()
        .map(|o| match &o.value {
            E::K(_) => None,
            E::N(_, id) => Some(*id),
        })
        .collect();
    // Group outputs into parts under the statement limit.
    let mut groups: Vec<Vec<usize>> = vec![Vec::new()];
    for (i, id) in ids.iter().enumerate() {
        let current = groups.last_mut().expect("non-empty");
        current.push(i);
        let size = part_size(&graph, current, &ids);
        if size > MAX_STATEMENTS && current.len() > 1 {
            current.pop();
            groups.push(vec![i]);
        }
        let _ = id;
    }
    let mut ops = OpCount::default();
    let parts = groups
        .into_iter()
        .filter(|grp| !grp.is_empty())
        .map(|grp| {
            let roots: Vec<Id> = grp.iter().filter_map(|&i| ids[i]).collect();
            ops += count(&graph, roots.iter().copied());
            let mut stmts = Vec::new();
            let mut names: HashMap<Id, TokenStream> = HashMap::new();
            let mut temp = 0usize;
            for id in reachable(&graph, roots) {
                let name = match graph.node(id) {
                    Node::Sym(s) => {
                        let (n, load) = sym_load(s);
                        stmts.push(quote!(let #n: T = #load;));
                        quote!(#n)
                    }
                    Node::Const(bits) => {
                        let n = ident(&format!("k{temp}"));
                        temp += 1;
                        let c = constant(f64::from_bits(bits));
                        stmts.push(quote!(let #n: T = #c;));
                        quote!(#n)
                    }
                    node => {
                        let n = ident(&format!("t{temp}"));
                        temp += 1;
                        let v = |x: Id| names[&x].clone();
                        let rhs = match node {
                            Node::Add(a, b) => {
                                let (a, b) = (v(a), v(b));
                                quote!(#a + #b)
                            }
                            Node::Sub(a, b) => {
                                let (a, b) = (v(a), v(b));
                                quote!(#a - #b)
                            }
                            Node::Mul(a, b) => {
                                let (a, b) = (v(a), v(b));
                                quote!(#a * #b)
                            }
                            Node::Div(a, b) => {
                                let (a, b) = (v(a), v(b));
                                quote!(#a / #b)
                            }
                            Node::Neg(a) => {
                                let a = v(a);
                                quote!(-#a)
                            }
                            Node::Sqrt(a) => {
                                let a = v(a);
                                quote!(#a.sqrt())
                            }
                            Node::Sym(_) | Node::Const(_) => unreachable!("handled above"),
                        };
                        stmts.push(quote!(let #n: T = #rhs;));
                        quote!(#n)
                    }
                };
                names.insert(id, name);
            }
            for &i in &grp {
                let target = &outputs[i].target;
                let value = match (&outputs[i].value, ids[i]) {
                    (_, Some(id)) => names[&id].clone(),
                    (E::K(x), None) => constant(*x),
                    (E::N(..), None) => unreachable!("nodes have ids"),
                };
                stmts.push(quote!(#target = #value;));
            }
            stmts
        })
        .collect();
    Emitted { parts, ops }
}

fn part_size(graph: &Graph, group: &[usize], ids: &[Option<Id>]) -> usize {
    reachable(graph, group.iter().filter_map(|&i| ids[i])).len() + group.len()
}

//! Scratch: op counts of each D candidate.
use dhgen_codegen::RobotModel;
use dhgen_codegen::derive::{Derivation, graph_chain, polys_to_exprs};
use dhgen_codegen::graph::{SharedGraph, count};
fn main() {
    for path in std::env::args().skip(1) {
        let model = RobotModel::from_toml_file(&path).unwrap();
        let dv = Derivation::new(&model);
        let g = SharedGraph::default();
        let polys: Vec<_> = dv.mass_matrix_polys().iter().flatten().cloned().collect();
        let terms: usize = polys.iter().map(|p| p.terms().len()).sum();
        let e = polys_to_exprs(&polys, &g, &model);
        let ids: Vec<_> = e.iter().map(|x| x.id_in(&g)).collect();
        let c1 = count(&g.borrow(), ids);
        let g2 = SharedGraph::default();
        let d = graph_chain(&model, &g2).mass_matrix();
        let ids: Vec<_> = d.iter().flatten().map(|x| x.id_in(&g2)).collect();
        let c2 = count(&g2.borrow(), ids);
        println!(
            "{}: normal form {} terms, horner {:?} total {}, crba {:?} total {}",
            model.name,
            terms,
            c1,
            c1.total(),
            c2,
            c2.total()
        );
    }
}

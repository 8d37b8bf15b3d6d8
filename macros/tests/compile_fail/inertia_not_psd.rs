// An inertia tensor with a negative principal moment (rejected even with
// `allow_nonphysical_inertia`, which only turns off the triangle inequality).
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        allow_nonphysical_inertia: true,
        links: [
            {
                joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0,
                mass: 2.0, com: [-0.5, 0.0, 0.0], inertia: { xx: -1.0, yy: 1.0, zz: 3.0 },
            },
        ],
    }
}

fn main() {}

//! Generated code against the runtime path, on random configurations, for every catalogue
//! robot and for the fixtures `odd`, `gantry`, `snake17` and `oblique9` (tests/fixtures), which
//! cover what the reference files do not (prismatic joints, modified DH with base and tool,
//! tilted gravity, motors and friction, more joints than the normal form holds, an arm with no
//! quarter turn or zero anywhere).

use crate::catalogue::{
    cylindrical, gantry, oblique9, odd, panda, planar_elbow, puma560, scara, snake17, stanford, ur5,
};
use crate::support::{fixture, max_abs, runtime};
use dhgen::Robot;
use proptest::prelude::*;

fn close(what: &str, got: f64, want: f64, scale: f64) -> Result<(), TestCaseError> {
    let err = (got - want).abs() / scale.max(1.0);
    prop_assert!(
        err <= 1e-12,
        "{what}: generated {got}, runtime {want}, relative error {err:e}"
    );
    Ok(())
}

macro_rules! compare {
    ($test:ident, $m:ident, $robot:expr) => {
        compare!($test, $m, $robot, |st, robot, q, qd, qdd| {
            const N: usize = $m::DOF;
            dynamics::<N>(robot, q, qd, qdd, &st.mass_matrix(), &st.christoffel(),
                &st.coriolis(qd), &st.gravity(), &st.inverse_dynamics(qd, qdd))?;
            energy_and_bias::<N>(robot, q, qd, [st.kinetic_energy(qd), st.potential_energy()],
                &st.bias(qd))?;
            centre_of_mass::<N>(robot, q, st.center_of_mass(), &st.center_of_mass_jacobian())
        });
    };
    ($test:ident, $m:ident, $robot:expr, kinematics) => {
        compare!($test, $m, $robot, |_st, _robot, _q, _qd, _qdd| Ok(()));
    };
    ($test:ident, $m:ident, $robot:expr, $dynamics:expr) => {
        proptest! {
            #![proptest_config(ProptestConfig::with_cases(64))]
            #[test]
            fn $test(
                q in proptest::array::uniform::<_, { $m::DOF }>(-3.0f64..3.0),
                qd in proptest::array::uniform::<_, { $m::DOF }>(-2.0f64..2.0),
                qdd in proptest::array::uniform::<_, { $m::DOF }>(-2.0f64..2.0),
            ) {
                const N: usize = $m::DOF;
                let robot = $robot;
                let st = $m::State::new(&q);
                let t = st.fk().to_homogeneous();
                let tr = robot.fk(&q).to_homogeneous();
                for i in 0..16 {
                    close("T", t[i], tr[i], 1.0)?;
                }
                for (f, fr) in st.frames().iter().zip(robot.frames(&q)) {
                    let (a, b) = (f.to_homogeneous(), fr.to_homogeneous());
                    for i in 0..16 {
                        close("frame", a[i], b[i], 1.0)?;
                    }
                }
                let j = st.jacobian();
                let jr = robot.jacobian(&q);
                for c in 0..N {
                    for r in 0..6 {
                        close("J", j[(r, c)], jr[(r, c)], 1.0)?;
                    }
                }
                let check: fn(&$m::State<f64>, &Robot, &[f64; N], &[f64; N], &[f64; N]) -> Result<(), TestCaseError> = $dynamics;
                check(&st, &robot, &q, &qd, &qdd)?;
            }
        }
    };
}

#[allow(clippy::too_many_arguments)]
fn dynamics<const N: usize>(
    robot: &Robot,
    q: &[f64; N],
    qd: &[f64; N],
    qdd: &[f64; N],
    d: &dhgen::nalgebra::SMatrix<f64, N, N>,
    c: &[[[f64; N]; N]; N],
    cor: &dhgen::nalgebra::SMatrix<f64, N, N>,
    g: &dhgen::nalgebra::SVector<f64, N>,
    tau: &dhgen::nalgebra::SVector<f64, N>,
) -> Result<(), TestCaseError> {
    let dr = robot.mass_matrix(q);
    let s = max_abs(dr.iter().copied());
    for i in 0..N * N {
        close("D", d[i], dr[i], s)?;
    }
    let cr = robot.christoffel(q);
    let s = (0..N)
        .flat_map(|i| (0..N).flat_map(move |j| (0..N).map(move |k| (i, j, k))))
        .fold(0.0f64, |m, (i, j, k)| m.max(cr[i][j][k].abs()));
    for i in 0..N {
        for j in 0..N {
            for k in 0..N {
                close("c_ijk", c[i][j][k], cr[i][j][k], s)?;
            }
        }
    }
    let corr = robot.coriolis(q, qd);
    let s = max_abs(corr.iter().copied());
    for i in 0..N * N {
        close("C", cor[i], corr[i], s)?;
    }
    let gr = robot.gravity(q);
    let s = max_abs(gr.iter().copied());
    for i in 0..N {
        close("g", g[i], gr[i], s)?;
    }
    let taur = robot.inverse_dynamics(q, qd, qdd);
    let s = max_abs(taur.iter().copied());
    for i in 0..N {
        close("tau", tau[i], taur[i], s)?;
    }
    Ok(())
}

/// The kinetic energy against the runtime path's `½ q̇ᵀ D q̇`, the potential energy against
/// the runtime walk, and the bias torques against the runtime RNEA at zero acceleration.
fn energy_and_bias<const N: usize>(
    robot: &Robot,
    q: &[f64; N],
    qd: &[f64; N],
    [kinetic, potential]: [f64; 2],
    bias: &dhgen::nalgebra::SVector<f64, N>,
) -> Result<(), TestCaseError> {
    let want = robot.kinetic_energy(q, qd);
    close("kinetic energy", kinetic, want, want.abs())?;
    let want = robot.potential_energy(q);
    close("potential energy", potential, want, want.abs())?;
    let br = robot.bias(q, qd);
    let s = max_abs(br.iter().copied());
    for i in 0..N {
        close("bias", bias[i], br[i], s)?;
    }
    Ok(())
}

/// The links' mass, centre of mass and its Jacobian against the runtime path's (the trait's
/// walk over the links' centres and Jacobians).
fn centre_of_mass<const N: usize>(
    robot: &Robot,
    q: &[f64; N],
    (mass, c): (f64, dhgen::nalgebra::Point3<f64>),
    jc: &dhgen::nalgebra::SMatrix<f64, 3, N>,
) -> Result<(), TestCaseError> {
    let (want_mass, want_c) = robot.center_of_mass(q);
    close("M", mass, want_mass, want_mass)?;
    for i in 0..3 {
        close("c", c[i], want_c[i], 1.0)?;
    }
    let jr = robot.center_of_mass_jacobian(q);
    for i in 0..3 * N {
        close("J_c", jc[i], jr[i], 1.0)?;
    }
    Ok(())
}

compare!(
    planar_elbow_generated_equals_runtime,
    planar_elbow,
    runtime("planar_elbow")
);
compare!(
    puma560_generated_equals_runtime,
    puma560,
    runtime("puma560")
);
compare!(
    stanford_generated_equals_runtime,
    stanford,
    runtime("stanford")
);
compare!(panda_generated_equals_runtime, panda, runtime("panda"));
compare!(scara_generated_equals_runtime, scara, runtime("scara"));
compare!(ur5_generated_equals_runtime, ur5, runtime("ur5"));
compare!(
    cylindrical_generated_equals_runtime,
    cylindrical,
    runtime("cylindrical"),
    kinematics
);
compare!(odd_generated_equals_runtime, odd, fixture("odd"));
compare!(gantry_generated_equals_runtime, gantry, fixture("gantry"));
compare!(
    snake17_generated_equals_runtime,
    snake17,
    fixture("snake17")
);
compare!(
    oblique9_generated_equals_runtime,
    oblique9,
    fixture("oblique9")
);

/// f32 instantiation of the same generated code agrees with f64 to f32 precision.
#[test]
fn f32_matches_f64() {
    let q = [0.3, -1.1, 0.7, 2.0, -0.4, 1.3, 0.2];
    let qd = [0.5, -0.2, 0.1, 0.9, -1.0, 0.3, 0.7];
    let qdd = [1.0, 0.4, -0.6, 0.2, 0.8, -0.3, 0.1];
    let f = |a: [f64; 7]| a.map(|x| x as f32);
    let d64 = panda::mass_matrix(&q);
    let d32 = panda::mass_matrix(&f(q));
    let t64 = panda::inverse_dynamics(&q, &qd, &qdd);
    let t32 = panda::inverse_dynamics(&f(q), &f(qd), &f(qdd));
    let p64 = panda::fk(&q).translation.vector;
    let p32 = panda::fk(&f(q)).translation.vector;
    let tol = 1e-5;
    for i in 0..49 {
        assert!(
            (f64::from(d32[i]) - d64[i]).abs() <= tol * d64.amax(),
            "D[{i}]"
        );
    }
    for i in 0..7 {
        assert!(
            (f64::from(t32[i]) - t64[i]).abs() <= tol * t64.amax(),
            "tau[{i}]"
        );
    }
    for i in 0..3 {
        assert!((f64::from(p32[i]) - p64[i]).abs() <= tol, "p[{i}]");
    }
}

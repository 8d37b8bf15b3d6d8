//! The value types generated functions return, and where each scalar of a derivation goes.

use proc_macro2::TokenStream;
use quote::quote;

/// What a generated function returns, generic over the scalar `T` (or `f64` in trait impls).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// A scalar.
    Scalar,
    /// A 4×4 homogeneous transform; derivations give the top three rows, row by row.
    Homogeneous,
    /// One homogeneous transform per joint.
    HomogeneousPerJoint,
    /// A pose as an `Isometry3`.
    Pose,
    /// One pose per joint.
    PosePerJoint,
    /// A 6-vector (a twist or its rate).
    Vector6,
    /// A 6×n matrix, column by column.
    Jacobian,
    /// A mass and a point: `(M, c)`, the mass first.
    MassAndPoint,
    /// A 3×n matrix, column by column.
    PointJacobian,
    /// One value per joint.
    Vector,
    /// An optional value per joint.
    OptionVector,
    /// One value per joint and the mask of the lanes where it is valid.
    VectorMask,
    /// An n×n matrix and the mask of the lanes where it is valid.
    SquareMask,
    /// An n×n matrix, row by row.
    Square,
    /// Two n×n matrices, each row by row, the first then the second.
    SquarePair,
    /// Three n×n matrices, each row by row, in turn.
    SquareTriple,
    /// An optional n×n matrix.
    OptionSquare,
    /// Three optional n×n matrices.
    OptionSquareTriple,
    /// Three n×n matrices and the mask of the lanes where they are valid.
    SquareTripleMask,
    /// An n×n×n array `[i][j][k]`.
    Cube,
    /// The `Terms` struct.
    Terms,
    /// `dhgen::task_space::ToolTerms`.
    ToolTerms,
    /// The regressor, n × `PARAMETERS`, row by row.
    Regressor,
    /// The base regressor, n × `BASE_PARAMETERS`, row by row.
    BaseRegressor,
}

impl Shape {
    /// The type, with scalar `t`.
    pub fn ty(self, t: &TokenStream) -> TokenStream {
        match self {
            Shape::Scalar => quote!(#t),
            Shape::Homogeneous => quote!(na::Matrix4<#t>),
            Shape::HomogeneousPerJoint => quote!([na::Matrix4<#t>; DOF]),
            Shape::Pose => quote!(na::Isometry3<#t>),
            Shape::PosePerJoint => quote!([na::Isometry3<#t>; DOF]),
            Shape::Vector6 => quote!(na::SVector<#t, 6>),
            Shape::Jacobian => quote!(na::SMatrix<#t, 6, DOF>),
            Shape::MassAndPoint => quote!((#t, na::Point3<#t>)),
            Shape::PointJacobian => quote!(na::SMatrix<#t, 3, DOF>),
            Shape::Vector => quote!(na::SVector<#t, DOF>),
            Shape::OptionVector => quote!(Option<na::SVector<#t, DOF>>),
            Shape::VectorMask => {
                quote!((na::SVector<#t, DOF>, <#t as na::SimdValue>::SimdBool))
            }
            Shape::SquareMask => {
                quote!((na::SMatrix<#t, DOF, DOF>, <#t as na::SimdValue>::SimdBool))
            }
            Shape::Square => quote!(na::SMatrix<#t, DOF, DOF>),
            Shape::SquarePair => quote!((na::SMatrix<#t, DOF, DOF>, na::SMatrix<#t, DOF, DOF>)),
            Shape::SquareTriple => quote!((
                na::SMatrix<#t, DOF, DOF>,
                na::SMatrix<#t, DOF, DOF>,
                na::SMatrix<#t, DOF, DOF>,
            )),
            Shape::OptionSquare => quote!(Option<na::SMatrix<#t, DOF, DOF>>),
            Shape::OptionSquareTriple => quote!(
                Option<(
                    na::SMatrix<#t, DOF, DOF>,
                    na::SMatrix<#t, DOF, DOF>,
                    na::SMatrix<#t, DOF, DOF>,
                )>
            ),
            Shape::SquareTripleMask => quote!((
                (
                    na::SMatrix<#t, DOF, DOF>,
                    na::SMatrix<#t, DOF, DOF>,
                    na::SMatrix<#t, DOF, DOF>,
                ),
                <#t as na::SimdValue>::SimdBool,
            )),
            Shape::Cube => quote!([[[#t; DOF]; DOF]; DOF]),
            Shape::Terms => quote!(Terms<#t>),
            Shape::ToolTerms => quote!(::dhgen::__private::ToolTerms<#t, na::Const<DOF>>),
            Shape::Regressor => quote!(na::SMatrix<#t, DOF, PARAMETERS>),
            Shape::BaseRegressor => quote!(na::SMatrix<#t, DOF, BASE_PARAMETERS>),
        }
    }

    /// The initial value of a derived output, before its entries are stored (`None` for a
    /// scalar, which is assigned exactly once).
    pub fn init(self) -> Option<TokenStream> {
        // Matrices are built from arrays (`ArrayStorage` is column-major): nalgebra's
        // `zeros()` and `identity()` fill through an iterator that, for a SIMD pack, compiles
        // to a loop of overlapping stores and loads (store-forwarding stalls: Panda's D on
        // packs of four took 3× its arithmetic).
        let zeros = |r: TokenStream, c: TokenStream| quote!(na::Matrix::from_data(na::ArrayStorage([[T::zero(); #r]; #c])));
        let identity = quote!({
            let (z, o) = (T::zero(), T::one());
            na::Matrix4::from_data(na::ArrayStorage([
                [o, z, z, z],
                [z, o, z, z],
                [z, z, o, z],
                [z, z, z, o],
            ]))
        });
        match self {
            Shape::Scalar => None,
            Shape::Homogeneous => Some(identity),
            Shape::HomogeneousPerJoint => Some(quote!([#identity; DOF])),
            Shape::Vector6 => Some(zeros(quote!(6), quote!(1))),
            Shape::Jacobian => Some(zeros(quote!(6), quote!(DOF))),
            Shape::MassAndPoint => Some(quote!((T::zero(), na::Point3::origin()))),
            Shape::PointJacobian => Some(zeros(quote!(3), quote!(DOF))),
            Shape::Square => Some(zeros(quote!(DOF), quote!(DOF))),
            Shape::Regressor => Some(zeros(quote!(DOF), quote!(PARAMETERS))),
            Shape::BaseRegressor => Some(zeros(quote!(DOF), quote!(BASE_PARAMETERS))),
            Shape::SquarePair => {
                let z = zeros(quote!(DOF), quote!(DOF));
                Some(quote!((#z, #z)))
            }
            Shape::SquareTriple => {
                let z = zeros(quote!(DOF), quote!(DOF));
                Some(quote!((#z, #z, #z)))
            }
            Shape::Vector => Some(zeros(quote!(DOF), quote!(1))),
            Shape::Cube => Some(quote!([[[T::zero(); DOF]; DOF]; DOF])),
            Shape::Pose
            | Shape::PosePerJoint
            | Shape::OptionVector
            | Shape::VectorMask
            | Shape::SquareMask
            | Shape::OptionSquare
            | Shape::OptionSquareTriple
            | Shape::SquareTripleMask
            | Shape::Terms
            | Shape::ToolTerms => {
                unreachable!("{self:?} values are composed, never derived entry by entry")
            }
        }
    }

    /// Where the `entries` scalars of a derivation go, in the order the derivation lists them
    /// (`n` joints).
    pub fn targets(self, n: usize, entries: usize) -> Vec<TokenStream> {
        let homogeneous = |out: TokenStream| -> Vec<TokenStream> {
            let mut v = Vec::with_capacity(12);
            for r in 0..3usize {
                for c in 0..4usize {
                    v.push(quote!(#out[(#r, #c)]));
                }
            }
            v
        };
        match self {
            Shape::Scalar => vec![quote!(out)],
            Shape::Homogeneous => homogeneous(quote!(out)),
            Shape::HomogeneousPerJoint => {
                (0..n).flat_map(|i| homogeneous(quote!(out[#i]))).collect()
            }
            Shape::Vector6 => (0..6usize).map(|i| quote!(out[#i])).collect(),
            Shape::Jacobian => (0..n)
                .flat_map(|c| (0..6usize).map(move |r| quote!(out[(#r, #c)])))
                .collect(),
            Shape::MassAndPoint => std::iter::once(quote!(out.0))
                .chain((0..3usize).map(|i| quote!(out.1[#i])))
                .collect(),
            Shape::PointJacobian => (0..n)
                .flat_map(|c| (0..3usize).map(move |r| quote!(out[(#r, #c)])))
                .collect(),
            Shape::Vector => (0..n).map(|i| quote!(out[#i])).collect(),
            Shape::Square => (0..n * n)
                .map(|idx| {
                    let (r, c) = (idx / n, idx % n);
                    quote!(out[(#r, #c)])
                })
                .collect(),
            Shape::Regressor | Shape::BaseRegressor => {
                let width = entries / n;
                (0..entries)
                    .map(|idx| {
                        let (r, c) = (idx / width, idx % width);
                        quote!(out[(#r, #c)])
                    })
                    .collect()
            }
            Shape::SquarePair | Shape::SquareTriple => (0..entries)
                .map(|idx| {
                    let (m, r, c) = (idx / (n * n), (idx / n) % n, idx % n);
                    let m = proc_macro2::Literal::usize_unsuffixed(m);
                    quote!(out.#m[(#r, #c)])
                })
                .collect(),
            Shape::Cube => (0..n * n * n)
                .map(|idx| {
                    let (i, j, k) = (idx / (n * n), (idx / n) % n, idx % n);
                    quote!(out[#i][#j][#k])
                })
                .collect(),
            Shape::Pose
            | Shape::PosePerJoint
            | Shape::OptionVector
            | Shape::VectorMask
            | Shape::SquareMask
            | Shape::OptionSquare
            | Shape::OptionSquareTriple
            | Shape::SquareTripleMask
            | Shape::Terms
            | Shape::ToolTerms => {
                unreachable!("{self:?} values are composed, never derived entry by entry")
            }
        }
    }
}

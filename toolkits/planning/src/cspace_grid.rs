//! The configuration-space obstacle region `QO = {q : A(q) ∩ O ≠ ∅}` (section 6.1) of a
//! 2-joint arm, sampled on a grid over its joint ranges.
//!
//! A cell is occupied when the arm collides (margin 0) at the cell's centre. The grid draws
//! pictures of QO, and serves as the obstacles of a configuration-space potential field
//! ([`CSpaceGrid::obstacles`]): each 4-connected group of occupied cells is one obstacle,
//! whose distance from `q` is measured to the centres of its boundary cells (so to within
//! half a cell), while motions are checked on the arm itself by the
//! [`CollisionChecker`]. The joint ranges are treated as intervals:
//! the wrap-around of a revolute joint's angle is not used.

use super::potential::{CSpaceObstacles, distance};
use super::{CollisionChecker, PlanError};
use dhgen_kernel::{Arm, ArmAllocator, JointVector};
use nalgebra::{DefaultAllocator, U1};

/// QO of a 2-joint arm on a grid.
#[derive(Clone, Debug, PartialEq)]
pub struct CSpaceGrid {
    bounds: [[f64; 2]; 2],
    cells: [usize; 2],
    /// Per cell, row-major over `(i, j)` (i along q1): 0 when free, else 1 + its component.
    labels: Vec<u32>,
    /// Per component, the centres of its cells that have a free 4-neighbour.
    boundaries: Vec<Vec<[f64; 2]>>,
}

impl CSpaceGrid {
    /// The most cells a grid takes: 4096 × 4096, five bytes each while it is built (about
    /// 80 MB) and one collision check each (tens of seconds). A larger request is an
    /// [`InvalidParameter`](PlanError::InvalidParameter), not an allocation that fails
    /// (which aborts the process).
    pub const MAX_CELLS: usize = 1 << 24;

    /// Samples QO on `cells[0] × cells[1]` cells over the joint ranges (the limits, or
    /// `[−π, π]` for a revolute joint without them), at most [`MAX_CELLS`](Self::MAX_CELLS).
    pub fn compute<A: Arm>(
        checker: &mut CollisionChecker<'_, A>,
        cells: [usize; 2],
    ) -> Result<CSpaceGrid, PlanError>
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        if checker.dof() != 2 {
            return Err(PlanError::InvalidGeometry(format!(
                "a C-space grid needs a 2-joint arm; this one has {} joints",
                checker.dof()
            )));
        }
        if cells.contains(&0) {
            return Err(PlanError::InvalidParameter {
                name: "cells",
                reason: format!("{cells:?}: need at least one cell per axis"),
            });
        }
        let count = match cells[0].checked_mul(cells[1]) {
            Some(count) if count <= Self::MAX_CELLS => count,
            _ => {
                return Err(PlanError::InvalidParameter {
                    name: "cells",
                    reason: format!(
                        "{cells:?}: more than CSpaceGrid::MAX_CELLS = {} cells",
                        Self::MAX_CELLS
                    ),
                });
            }
        };
        let arm = checker.arm();
        let bounds = [checker.joint_range(0), checker.joint_range(1)];
        let mut grid = CSpaceGrid {
            bounds,
            cells,
            labels: vec![0; count],
            boundaries: Vec::new(),
        };
        let mut occupied = vec![false; count];
        for i in 0..cells[0] {
            for j in 0..cells[1] {
                let c = grid.cell_center(i, j);
                let q = JointVector::<A>::from_column_slice_generic(arm.dim(), U1, &c);
                occupied[i * cells[1] + j] = checker.in_collision(&q);
            }
        }
        grid.label(&occupied);
        Ok(grid)
    }

    /// Labels the 4-connected components of the occupied cells and collects their
    /// boundary cells.
    fn label(&mut self, occupied: &[bool]) {
        let [ni, nj] = self.cells;
        let neighbours = |i: usize, j: usize| {
            [
                (i > 0).then(|| (i - 1, j)),
                (i + 1 < ni).then(|| (i + 1, j)),
                (j > 0).then(|| (i, j - 1)),
                (j + 1 < nj).then(|| (i, j + 1)),
            ]
            .into_iter()
            .flatten()
        };
        let mut stack = Vec::new();
        for start in 0..ni * nj {
            if !occupied[start] || self.labels[start] != 0 {
                continue;
            }
            let label = self.boundaries.len() as u32 + 1;
            let mut boundary = Vec::new();
            self.labels[start] = label;
            stack.push((start / nj, start % nj));
            while let Some((i, j)) = stack.pop() {
                let mut on_boundary = false;
                for (a, b) in neighbours(i, j) {
                    let k = a * nj + b;
                    if !occupied[k] {
                        on_boundary = true;
                    } else if self.labels[k] == 0 {
                        self.labels[k] = label;
                        stack.push((a, b));
                    }
                }
                if on_boundary {
                    boundary.push(self.cell_center(i, j));
                }
            }
            self.boundaries.push(boundary);
        }
    }

    /// Cells along q1 and q2.
    pub fn cells(&self) -> [usize; 2] {
        self.cells
    }

    /// The joint ranges covered, `[[q1 lower, q1 upper], [q2 lower, q2 upper]]`.
    pub fn bounds(&self) -> [[f64; 2]; 2] {
        self.bounds
    }

    /// The size of a cell along q1 and q2.
    pub fn cell_size(&self) -> [f64; 2] {
        [0, 1].map(|a| (self.bounds[a][1] - self.bounds[a][0]) / self.cells[a] as f64)
    }

    /// The configuration at the centre of cell `(i, j)`.
    pub fn cell_center(&self, i: usize, j: usize) -> [f64; 2] {
        let size = self.cell_size();
        [
            self.bounds[0][0] + (i as f64 + 0.5) * size[0],
            self.bounds[1][0] + (j as f64 + 0.5) * size[1],
        ]
    }

    /// Whether the arm collides at the centre of cell `(i, j)`.
    pub fn is_occupied(&self, i: usize, j: usize) -> bool {
        self.labels[i * self.cells[1] + j] != 0
    }

    /// The number of 4-connected components of QO on the grid.
    pub fn components(&self) -> usize {
        self.boundaries.len()
    }

    /// The share of cells that are occupied.
    pub fn occupied_fraction(&self) -> f64 {
        self.labels.iter().filter(|&&l| l != 0).count() as f64 / self.labels.len() as f64
    }

    /// The grid as the obstacles of a C-space potential field for the arm of `checker`,
    /// whose motions are checked on the arm at `resolution` (a finite number > 0, else
    /// [`PlanError::InvalidParameter`]).
    pub fn obstacles<'g, 'c, 'a, A: Arm>(
        &'g self,
        checker: &'c mut CollisionChecker<'a, A>,
        resolution: f64,
    ) -> Result<GridObstacles<'g, 'c, 'a, A>, PlanError>
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        if !(resolution > 0.0 && resolution.is_finite()) {
            return Err(PlanError::InvalidParameter {
                name: "resolution",
                reason: format!("{resolution} is not a finite number > 0"),
            });
        }
        Ok(GridObstacles {
            grid: self,
            checker,
            resolution,
        })
    }
}

/// A [`CSpaceGrid`] as [`CSpaceObstacles`]: distances from the grid, motions checked on the
/// arm.
pub struct GridObstacles<'g, 'c, 'a, A: Arm>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    grid: &'g CSpaceGrid,
    checker: &'c mut CollisionChecker<'a, A>,
    resolution: f64,
}

impl<A: Arm> CSpaceObstacles for GridObstacles<'_, '_, '_, A>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    fn dim(&self) -> usize {
        2
    }

    fn bounds(&self, j: usize) -> [f64; 2] {
        self.grid.bounds[j]
    }

    fn nearest(&mut self, q: &[f64], within: f64, visit: &mut dyn FnMut(f64, &[f64])) {
        for boundary in &self.grid.boundaries {
            let nearest = boundary
                .iter()
                .map(|b| (distance(q, b), b))
                .min_by(|x, y| x.0.total_cmp(&y.0));
            if let Some((rho, b)) = nearest.filter(|(rho, _)| *rho <= within) {
                visit(rho, b);
            }
        }
    }

    fn motion_is_free(&mut self, a: &[f64], b: &[f64]) -> bool {
        let dim = self.checker.arm().dim();
        let a = JointVector::<A>::from_column_slice_generic(dim, U1, a);
        let b = JointVector::<A>::from_column_slice_generic(dim, U1, b);
        self.checker.motion_is_free(&a, &b, self.resolution)
    }
}

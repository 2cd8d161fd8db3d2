//! The query path of a table with an `e_n` axis: [`Surface::eval_point`] bit for bit, with
//! a fine index per patch over `(γ, c, e_n)` in place of the octree's descent from its roots,
//! as [`super::Accel`] does for the quadtrees of an elastic table (the module documentation of
//! `fast` says why the bits are the rule's). The patch with its index is the same type for
//! both ([`IndexedPatch`] of 3 axes here, of 2 there), and the arithmetic of the leaf is the
//! rule's own (`oblique_table::leaf`).

use crate::LookupError;
use oblique_table::indexed::IndexedPatch;
use oblique_table::leaf::cubic_tensor;
#[cfg(target_arch = "x86_64")]
use oblique_table::leaf::cubic_tensor3_avx;
use oblique_table::surface::{
    full_slip_line, partial_coord_e, stick_coord, OutOfDomain, PatchKind, Region, Surface,
};

use super::MAX_INDEX_ENTRIES;

/// The acceleration structure of a table with an `e_n` axis: its patches with their fine
/// indexes.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Accel3 {
    alpha_max: f64,
    /// Indexed by `PatchId::index`.
    patches: [Option<IndexedPatch<3>>; 3],
}

impl Accel3 {
    /// The structure for a surface with an `e_n` axis and the cubic stencil, else `None`.
    pub(crate) fn new(surface: &Surface) -> Option<Accel3> {
        surface.restitution()?;
        if surface.stencil() != 4 {
            return None;
        }
        let mut patches: [Option<IndexedPatch<3>>; 3] = [None, None, None];
        for (id, p) in surface.patches() {
            patches[id.index()] = Some(IndexedPatch::new(p, MAX_INDEX_ENTRIES)?);
        }
        Some(Accel3 {
            alpha_max: surface.alpha_max(),
            patches,
        })
    }

    /// Bytes held by the fine indexes and cell lists (not counting the copy of `P`).
    pub(crate) fn index_bytes(&self) -> usize {
        self.patches
            .iter()
            .flatten()
            .map(IndexedPatch::index_bytes)
            .sum()
    }

    /// [`Surface::eval_point`], bit for bit. The checks and the full-slip line are inlined
    /// into the caller; the patches are answered out of line ([`Accel3::eval_off_line`]), as
    /// [`super::Accel::eval_with`] does.
    #[inline(always)]
    pub(crate) fn eval(
        &self,
        surface: &Surface,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        oblique_table::surface::check_query(gamma, alpha)?;
        surface.check_e_n(e_n)?;
        let region = Region::of_e(gamma, alpha, e_n);
        if region == Region::Line {
            return Ok(full_slip_line(alpha, e_n));
        }
        #[cfg(target_arch = "x86_64")]
        if cfg!(target_feature = "avx") || std::is_x86_feature_detected!("avx") {
            // SAFETY: the processor has AVX (checked just above, or enabled for the build).
            return unsafe { self.eval_off_line_avx(surface, region, gamma, alpha, e_n, outside) };
        }
        self.eval_off_line(surface, region, gamma, alpha, e_n, outside)
    }

    /// [`Accel3::eval`] for a valid query above the full-slip line.
    #[inline(never)]
    fn eval_off_line(
        &self,
        surface: &Surface,
        region: Region,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        surface.apply_domain_e(region, gamma, alpha, e_n, outside, |r, g, a| {
            self.eval_in(r, g, a, e_n, cubic_tensor)
        })
    }

    /// [`Accel3::eval_off_line`] compiled for AVX, with the leaf's sum in 256-bit vectors
    /// ([`cubic_tensor3_avx`], inlined here): the same operations, so the same bits (no
    /// product is fused with a sum: FMA is not enabled).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline(never)]
    fn eval_off_line_avx(
        &self,
        surface: &Surface,
        region: Region,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        surface.apply_domain_e(region, gamma, alpha, e_n, outside, |r, g, a| {
            self.eval_in(r, g, a, e_n, |vals, n1, f| cubic_tensor3_avx(vals, n1, f))
        })
    }

    /// In a known non-line region: the patch's coordinate, then its tensor product from
    /// `tensor` ([`IndexedPatch::interpolate_by`]).
    #[inline(always)]
    fn eval_in(
        &self,
        region: Region,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        tensor: impl Fn(&[f64], usize, [f64; 3]) -> f64,
    ) -> f64 {
        let patch = match region.patch_id() {
            Some(id) => self.patches[id.index()].as_ref(),
            None => None,
        };
        match patch {
            Some(patch) => {
                let c = match patch.kind() {
                    PatchKind::PartialSlip => partial_coord_e(gamma, alpha, e_n),
                    PatchKind::Stick => stick_coord(gamma, alpha, self.alpha_max),
                };
                patch.interpolate_by([gamma, c.clamp(0.0, 1.0), e_n], tensor)
            }
            None => -e_n,
        }
    }
}

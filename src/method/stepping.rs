//! Ray stepping: how the direction `p − eye` advances from pixel to pixel, one strategy
//! type per [`Stepping`](crate::Stepping) choice, each with its proven error bound.
//!
//! The frame-level [`Stepper`] hands out a small per-row [`RowStep`] by value, so the
//! pixel loop keeps it in registers. All three start from the camera's per-frame
//! [`CameraSteps`].

use crate::camera::Camera;
use crate::math::vec3::Vec3;
use crate::math::UNIT_ROUNDOFF;

/// How the ray direction advances: a strategy type per [`Stepping`](crate::Stepping).
pub(crate) trait Stepper {
    /// The per-row stepper.
    type Row: RowStep;
    fn new(camera: &Camera) -> Self;
    /// A bound `E` on `|d − (F + i·du + j·dv)|` (exact arithmetic on the camera's f32
    /// `F`, `du`, `dv`) over the whole image, for span culling's margin.
    ///
    /// Each f32
    /// addition or product rounds by at most 2⁻²⁴ of its result's norm.
    fn error_bound(camera: &Camera) -> f32;
    /// Prepare row `j`, starting at column `i0`.
    ///
    /// Rows come in increasing order.
    fn start_row(&mut self, j: u32, i0: u32) -> Self::Row;
}

/// A row's direction stepper.
pub(crate) trait RowStep {
    /// The current pixel's direction `p − eye`; advances one pixel.
    fn next_direction(&mut self) -> Vec3;
}

/// The camera's per-frame steps, camera-relative: the upper-left pixel's direction
/// `F = p(0,0) − eye`, the column step `du = pw·u` and the row step `dv = −ph·v`.
#[derive(Clone, Copy)]
pub(crate) struct CameraSteps {
    first: Vec3,
    du: Vec3,
    dv: Vec3,
}

impl CameraSteps {
    fn new(camera: &Camera) -> Self {
        Self {
            first: camera.first_direction(),
            du: camera.pixel_step(),
            dv: camera.scanline_step(),
        }
    }

    /// Row `j`'s first direction, `F + dv·j`, evaluated directly (two roundings).
    #[inline(always)]
    fn row(&self, j: u32) -> Vec3 {
        self.first + self.dv * j as f32
    }
}

/// `(|F| + H·|dv| + W·|du|, W, H)`: the largest ideal direction and the image size.
fn extent(camera: &Camera) -> (f32, f32, f32) {
    let size = camera.size();
    let (w, h) = (size.width as f32, size.height as f32);
    let s = camera.first_direction().length()
        + h * camera.scanline_step().length()
        + w * camera.pixel_step().length();
    (s, w, h)
}

/// 2⁻²³: twice the unit roundoff, a safety factor of 2 on every count below.
const ROUNDING: f32 = 2.0 * UNIT_ROUNDOFF;

/// [`Stepping::WorldSpace`](crate::Stepping::WorldSpace): the slides' world-space pixel centres.
pub(crate) struct WorldSpaceStep {
    eye: Vec3,
    du: Vec3,
    dv: Vec3,
    scanline_start: Vec3,
    /// The row `scanline_start` belongs to.
    row: u32,
}

/// A world-space row: the pixel centre, stepped by `du`.
pub(crate) struct WorldSpaceRow {
    eye: Vec3,
    du: Vec3,
    pixel_center: Vec3,
}

impl Stepper for WorldSpaceStep {
    type Row = WorldSpaceRow;

    fn error_bound(camera: &Camera) -> f32 {
        // `upper_left_world` (≤ 6 roundings of size |eye| + S), j additions of dv and
        // i additions of du (each ≤ 2⁻²⁴·|p|, |p| ≤ |eye| + S), and `p − eye`.
        let (s, w, h) = extent(camera);
        ROUNDING * (w + h + 8.0) * (camera.eye().length() + s)
    }

    fn new(camera: &Camera) -> Self {
        Self {
            eye: camera.eye(),
            du: camera.pixel_step(),
            dv: camera.scanline_step(),
            scanline_start: camera.upper_left_world(),
            row: 0,
        }
    }

    fn start_row(&mut self, j: u32, i0: u32) -> WorldSpaceRow {
        // scanlineStart −= ph·v, once per scanline (also for clipped rows, so a clipped
        // render sees exactly the rounding of a full one).
        while self.row < j {
            self.scanline_start += self.dv;
            self.row += 1;
        }
        let mut pixel_center = self.scanline_start;
        for _ in 0..i0 {
            pixel_center += self.du;
        }
        WorldSpaceRow {
            eye: self.eye,
            du: self.du,
            pixel_center,
        }
    }
}

impl RowStep for WorldSpaceRow {
    #[inline(always)]
    fn next_direction(&mut self) -> Vec3 {
        let d = self.pixel_center - self.eye;
        self.pixel_center += self.du;
        d
    }
}

/// [`Stepping::Incremental`](crate::Stepping::Incremental): camera-relative stepping
/// with each row anchored directly.
pub(crate) struct IncrementalStep(CameraSteps);

/// An incremental row: the direction, stepped by `du`.
pub(crate) struct IncrementalRow {
    du: Vec3,
    d: Vec3,
}

impl Stepper for IncrementalStep {
    type Row = IncrementalRow;

    fn error_bound(camera: &Camera) -> f32 {
        // The row anchor `F + dv·j` (2 roundings) and i additions of du (≤ 2⁻²⁴·S each).
        let (s, w, _) = extent(camera);
        ROUNDING * (w + 4.0) * s
    }

    fn new(camera: &Camera) -> Self {
        Self(CameraSteps::new(camera))
    }

    fn start_row(&mut self, j: u32, i0: u32) -> IncrementalRow {
        // Anchor the scanline exactly (per-row work), then step to the first visible
        // column the same way the pixel loop does.
        let mut d = self.0.row(j);
        for _ in 0..i0 {
            d += self.0.du;
        }
        IncrementalRow { du: self.0.du, d }
    }
}

impl RowStep for IncrementalRow {
    #[inline(always)]
    fn next_direction(&mut self) -> Vec3 {
        let d = self.d;
        self.d += self.du;
        d
    }
}

/// [`Stepping::Direct`](crate::Stepping::Direct): every pixel's direction evaluated directly.
pub(crate) struct DirectStep(CameraSteps);

/// A direct row: the row's first direction and the column.
pub(crate) struct DirectRow {
    row: Vec3,
    du: Vec3,
    i: u32,
}

impl Stepper for DirectStep {
    type Row = DirectRow;

    fn error_bound(camera: &Camera) -> f32 {
        // `F + dv·j` and `+ du·i`: four roundings of size ≤ S.
        let (s, _, _) = extent(camera);
        ROUNDING * 8.0 * s
    }

    fn new(camera: &Camera) -> Self {
        Self(CameraSteps::new(camera))
    }

    fn start_row(&mut self, j: u32, i0: u32) -> DirectRow {
        DirectRow {
            row: self.0.row(j),
            du: self.0.du,
            i: i0,
        }
    }
}

impl RowStep for DirectRow {
    #[inline(always)]
    fn next_direction(&mut self) -> Vec3 {
        let d = self.row + self.du * self.i as f32;
        self.i += 1;
        d
    }
}

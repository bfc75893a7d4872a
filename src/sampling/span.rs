//! [`Sampling::Adaptive`](super::Sampling::Adaptive)`(n)` on a Lab #1 scene: each
//! row's edge columns from the spheres' rings ([`ring`](super::ring)), merged into
//! sorted runs, and a row that averages only those.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use super::average::{average, SubSteps};
use super::grid::row_area;
use super::ring::{span_bands, SpanBands};
use super::shared::{own_area, AdaptiveRows};
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::trace::frame::{Frame, FrameSphere};
use crate::trace::options::Sample;
use crate::trace::rows::Rows;
use crate::trace::scanline::{self, ColorRuns, PixelRow, RowPixels, RowSink, RowTracer};
use crate::trace::shade::Shader;

/// [`Sampling::Adaptive`](super::Sampling::Adaptive)`(n)` for scenes whose colours
/// jump only at sphere silhouettes (Lab #1 on spheres): the edge pixels come from the
/// silhouettes alone, per row, and no sample is shared between pixels.
///
/// **Edge pixels**: once per frame each sphere gets two ellipses ([`SpanBands`]), its
/// silhouette enlarged and shrunk by the test's rounding margin and the larger of the
/// stepping's and the sub-pixel rays' direction errors (`camera/span.rs`); once per
/// row, the columns whose sub-sample square `[i ± h] × [j ± h]`, `h = (n − 1)/(2n)`,
/// reaches the enlarged one but is not inside the shrunk one are its edge columns. So
/// every pixel whose samples may see two different things (a sphere and the
/// background, or two spheres: between spheres that do not touch the one in front
/// never changes) is an edge pixel, however small the sphere;
/// `lab/tests/lab/sampling.rs` checks it sample by sample. Edge columns hidden by a
/// sphere in front that all the samples hit are dropped. A second ring per sphere marks
/// pixels where the centre's Lab #1 shade is not a fair stand-in for the mean (the
/// `0.3` floor's kink, and steep shading on small spheres;
/// [`SHADE_TOLERANCE`](super::ring::SHADE_TOLERANCE)) — a heuristic the quality tables
/// measure. This path keeps no row buffer: its cost is the centre row plus a few
/// interval comparisons per row, and it has no width limit.
///
/// A frame the silhouettes cannot decide ([`span_bands`]) — a sphere reaching the eye's
/// plane (one wholly behind the eye cannot be hit and is left out), two spheres closer
/// than a small gap, a fast square root — is drawn by [`AdaptiveRows`]' shared samples;
/// `clip` is the render's own, and the frame is ringed for that case.
#[derive(Clone, Copy)]
pub(crate) struct SpanAdaptiveRows {
    pub n: u32,
    pub clip: Rectangle,
}

/// Per row: a sphere some ray of the row's pixels can hit (`lo..hi`: the columns
/// whose samples can hit it), and the row's edge columns for it: four intervals (the
/// silhouette's ring on either side, the shading ring on either side), empty ones as
/// `(x, x)`.
struct Band<'s, T: TestStrategy, Sh: Shader> {
    index: usize,
    sphere: &'s FrameSphere<T, Sh>,
    lo: u32,
    hi: u32,
    /// The columns whose samples all hit it.
    inside: (u32, u32),
    edges: [(u32, u32); 4],
}

/// A row's edge columns as runs `[lo, hi)` in increasing order, disjoint and not
/// touching: the union of the bands' edge intervals (`edges`, four per band, empty
/// ones as `(x, x)`), sorted and merged once per row so that each pixel pays one
/// comparison.
///
/// Built in `runs`; returns how many of its intervals (flattened, from the first) are
/// runs.
fn edge_runs<const N: usize>(
    edges: impl Iterator<Item = [(u32, u32); 4]>,
    runs: &mut Vec<[(u32, u32); 4], N>,
) -> usize {
    runs.clear();
    for e in edges {
        // Never fails: one per band, at most one band per sphere.
        let _ = runs.push(e);
    }
    let all = runs.as_flattened_mut();
    // The non-empty intervals to the front, sorted by their start: an insertion sort
    // (a few dozen at most, mostly in order already). Slots before `k` are free once
    // read, so the sorted prefix (`m ≤ k`) may grow into them.
    let mut m: usize = 0;
    for k in 0..all.len() {
        let Some(&e) = all.get(k) else { break };
        if e.0 >= e.1 {
            continue;
        }
        let mut p = m;
        while let Some(&before) = p.checked_sub(1).and_then(|q| all.get(q)) {
            if before.0 <= e.0 {
                break;
            }
            if let Some(slot) = all.get_mut(p) {
                *slot = before;
            }
            p -= 1;
        }
        if let Some(slot) = all.get_mut(p) {
            *slot = e;
        }
        m += 1;
    }
    // Merge where they overlap or touch.
    let mut out: usize = 0;
    for k in 0..m {
        let Some(&(a, z)) = all.get(k) else { break };
        if let Some(last) = out.checked_sub(1).and_then(|q| all.get_mut(q)) {
            if a <= last.1 {
                last.1 = last.1.max(z);
                continue;
            }
        }
        if let Some(slot) = all.get_mut(out) {
            *slot = (a, z);
        }
        out += 1;
    }
    out
}

/// Whether a Lab #1 frame under [`Sampling::Adaptive`](super::Sampling::Adaptive)
/// shares samples between neighbours ([`AdaptiveRows`]) instead of taking its edges
/// from the silhouettes, decided exactly as [`SpanAdaptiveRows`]'s rows decide it.
///
/// One decision for the whole frame (a fast square root, or [`span_bands`] refusing:
/// two spheres anywhere that touch, a sphere reaching the eye's plane), which moves the
/// edge pixels of spheres that never moved; an incremental frame compares it. The
/// frame's spheres are built by `Frame::new` from the same setup (scale, cone, stepping
/// error) as `lab1.rs` builds them over the whole image: neither they nor `span_bands`
/// depend on the clip.
#[inline(never)]
pub(crate) fn shares_samples<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
>(
    scene: &crate::scene::Scene<N, L, P, D>,
    camera: &crate::camera::Camera,
    options: crate::trace::options::Options,
    (scale, culled): (crate::method::intersect::Scale, bool),
) -> bool {
    use crate::method::intersect::{Robust, AUTO_FD_CAPACITY};
    if !Q::EXACT {
        return true;
    }
    // `Auto` above its capacity limit is drawn with `Robust` or with forward
    // differences in a smaller frame (`lab1.rs`): the same margin either way, so the
    // same silhouettes and the same decision, on a smaller stack.
    if T::AUTO && N > AUTO_FD_CAPACITY {
        return shares_samples::<N, L, P, D, S, Robust, Q>(scene, camera, options, (scale, culled));
    }
    let mut spheres: Vec<FrameSphere<T, crate::trace::shade::Lab1>, N> = Vec::new();
    let image = Rectangle::new(embedded_graphics::prelude::Point::zero(), camera.size());
    let setup = crate::trace::frame::FrameSetup {
        camera,
        options,
        step_err: S::error_bound(camera),
        scale,
        culled,
    };
    Frame::new::<N, N, L, P, D, S>(scene, setup, image, image.top_left, &mut spheres)
        .is_some_and(|frame| span_bands::<N, S, T, crate::trace::shade::Lab1>(&frame).is_none())
}

impl Rows for SpanAdaptiveRows {
    const CENTER: bool = false;
    #[inline(always)]
    fn clip(&self, clip: Rectangle) -> Rectangle {
        // The ring the shared samples need if the frame falls back to them.
        AdaptiveRows { n: self.n, clip }.clip(clip)
    }

    // Out of line: the one-ray path's callers do not carry its frame on their stack.
    #[inline(never)]
    fn draw_rows<'s, const N: usize, K: RowSink, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X>(
        self,
        frame: &Frame<'s, T, Sh>,
        sink: &mut K,
        mut tracer: impl FnMut(u32, &mut u32, &mut u32) -> X,
    ) -> Result<(), K::Error>
    where
        X: RowTracer<'s, T, Sh>,
    {
        // A fast square root moves hits and their order by up to 6 %: nothing the
        // silhouettes' margins cover.
        let sils = if Q::EXACT {
            span_bands::<N, S, T, Sh>(frame)
        } else {
            None
        };
        let Some(sils) = sils else {
            let rows = AdaptiveRows {
                n: self.n,
                clip: self.clip,
            };
            return rows.draw_rows::<N, K, S, T, Q, Sh, X>(frame, sink, tracer);
        };
        // The render's own columns and rows inside the ringed frame.
        let Some(((ri0, ri1), (rj0, rj1))) = own_area(frame, self.clip) else {
            return Ok(());
        };
        let steps = SubSteps::new(frame, self.n);
        // Half the extent of the sub-sample grid, `(n − 1)/(2n)` pixels, widened for
        // the rounding of `i + o` (≤ 2⁻²⁴·(|i| + 1), below 2⁻¹¹ for i < 2¹³).
        let half = (self.n - 1) as f32 / (2 * self.n) as f32 + 1.0 / 2048.0;
        let mut stepper = S::new(frame.camera);
        let mut active: Vec<_, N> = Vec::new();
        let mut bands: Vec<Band<'s, T, Sh>, N> = Vec::new();
        let mut runs: Vec<[(u32, u32); 4], N> = Vec::new();
        for j in rj0..rj1 {
            let row_step = stepper.start_row(j, frame.i0);
            let (mut lo, mut hi) = scanline::activate(frame, &mut stepper, j, &mut active);
            let tracer = tracer(j, &mut lo, &mut hi);
            let mut row = RowPixels::<S, T, Q, Sh, X>::new(frame, row_step, &mut active, (lo, hi), tracer, j);
            // The ring's column on the left: traced, not drawn (a test's row state
            // expects every column of its span).
            for _ in frame.i0..ri0 {
                row.next_color();
            }
            row_bands(frame, &sils, j, half, &mut bands);
            let count = edge_runs(bands.iter().map(|b| b.edges), &mut runs);
            let mut span_row = SpanRow::<N, S, T, Q, Sh, X> {
                row,
                bands: &bands,
                steps: &steps,
                runs: runs.as_flattened().get(..count).unwrap_or_default(),
                next: 0,
                edge: (u32::MAX, u32::MAX),
                i: ri0,
                end: ri1,
                j,
            };
            span_row.next_run(ri0);
            sink.row(row_area(frame, ri0, ri1, j), span_row)?;
        }
        Ok(())
    }
}

/// Row `j`'s [`Band`]s (in scene order) for sub-samples within `half` pixels of the
/// centres: columns whose samples can reach a sphere's outer silhouette, and its edge
/// columns: those of the silhouette's ring and, by their centres, the shading ring's.
#[inline(never)]
fn row_bands<'s, const N: usize, T: TestStrategy, Sh: Shader>(
    frame: &Frame<'s, T, Sh>,
    sils: &[SpanBands],
    j: u32,
    half: f32,
    bands: &mut Vec<Band<'s, T, Sh>, N>,
) {
    bands.clear();
    let frame_columns = (frame.i0 as f32, frame.i1 as f32);
    for (index, (sphere, sil)) in frame.spheres.iter().zip(sils).enumerate() {
        let Some([lo, hi, in_lo, in_hi]) = sil
            .silhouette
            .as_ref()
            .and_then(|ring| ring.columns(j, half, frame_columns))
        else {
            continue;
        };
        // The shading ring's columns within the sphere's (its cap sphere can look
        // wider than the sphere when the eye is near).
        let shade = sil
            .shade
            .as_ref()
            .and_then(|ring| ring.columns(j, 0.0, frame_columns))
            .map_or([hi; 4], |c| c.map(|x| x.clamp(lo, hi)));
        // Never fails: one per sphere.
        let _ = bands.push(Band {
            index,
            sphere,
            lo,
            hi,
            inside: (in_lo, in_hi),
            edges: [
                (lo, in_lo),
                (in_hi, hi),
                (shade[0], shade[2]),
                (shade[3], shade[1]),
            ],
        });
    }
    // A sphere's edges are hidden where every sample hits a sphere in front of it
    // (`c = |L|² − r²`, the eye's power, is smaller for the one in front: the radical
    // plane separates two spheres that do not touch, and a ray that hits both crosses
    // it from the eye's side); trimmed at the ends, the common case of a narrow edge.
    for k in 0..bands.len() {
        let Some(b) = bands.get(k) else { continue };
        let (c, mut edges) = (b.sphere.geom.c, b.edges);
        for front in bands.iter().filter(|f| f.sphere.geom.c < c) {
            let (a, z) = front.inside;
            for e in &mut edges {
                if a <= e.0 && e.0 < z {
                    e.0 = z.min(e.1);
                }
                if a < e.1 && e.1 <= z {
                    e.1 = a.max(e.0);
                }
            }
        }
        if let Some(b) = bands.get_mut(k) {
            b.edges = edges;
        }
    }
}

/// One row of [`SpanAdaptiveRows`]: the centre rays as the one-ray loop traces them,
/// and in edge columns the average of the sub-pixel rays, each tested against the
/// spheres whose band holds the column.
struct SpanRow<'a, 'r, 's, const N: usize, S: Stepper, T: TestStrategy, Q, Sh: Shader, X> {
    row: RowPixels<'r, 's, S, T, Q, Sh, X>,
    bands: &'a [Band<'s, T, Sh>],
    steps: &'a SubSteps,
    /// The row's runs of edge columns ([`edge_runs`]), the index of the next one not
    /// yet taken, and the current or next one.
    runs: &'a [(u32, u32)],
    next: usize,
    edge: (u32, u32),
    i: u32,
    end: u32,
    j: u32,
}

impl<'s, const N: usize, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>>
    SpanRow<'_, '_, 's, N, S, T, Q, Sh, X>
{
    /// Whether column `i` (columns come in increasing order) is an edge column: one
    /// comparison before the next run of edge columns.
    #[inline(always)]
    fn is_edge(&mut self, i: u32) -> bool {
        if i < self.edge.0 {
            return false;
        }
        if i >= self.edge.1 {
            self.next_run(i);
        }
        i >= self.edge.0
    }

    /// Takes the first run still reaching past column `from` (`(u32::MAX, u32::MAX)`
    /// if none), starting at `from` at the earliest.
    #[inline(always)]
    fn next_run(&mut self, from: u32) {
        while let Some(&(lo, hi)) = self.runs.get(self.next) {
            self.next += 1;
            if hi > from {
                self.edge = (lo.max(from), hi);
                return;
            }
        }
        self.edge = (u32::MAX, u32::MAX);
    }

    /// Column `i`'s `Grid(n)` average over the spheres whose band holds it.
    #[inline(never)]
    fn averaged(&mut self, i: u32) -> Rgb888 {
        // The spheres some sample of this pixel can hit, once for its n² rays.
        let mut cands: Vec<(usize, &'s FrameSphere<T, Sh>), N> = Vec::new();
        for b in self.bands.iter().filter(|b| i.wrapping_sub(b.lo) < b.hi - b.lo) {
            // Never fails: one per sphere.
            let _ = cands.push((b.index, b.sphere));
        }
        average::<T, Q, Sh, X>(
            cands.iter().copied(),
            self.row.tracer_mut(),
            self.steps,
            i,
            self.j,
        )
    }
}

impl<'s, const N: usize, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> Iterator
    for SpanRow<'_, '_, 's, N, S, T, Q, Sh, X>
{
    type Item = Rgb888;

    #[inline(always)]
    fn next(&mut self) -> Option<Rgb888> {
        let i = self.i;
        if i >= self.end {
            return None;
        }
        self.i += 1;
        // The centre ray always: a test's row state (forward differences) expects
        // every column of its span.
        let center = self.row.next_color();
        Some(if self.is_edge(i) { self.averaged(i) } else { center })
    }

    /// The same pixels as [`Self::next`], a run at a time: the centre-ray columns up
    /// to the next edge run without its per-pixel test, then the run's averages.
    #[inline(always)]
    fn fold<B, F: FnMut(B, Rgb888) -> B>(mut self, init: B, mut f: F) -> B {
        let mut acc = init;
        while self.i < self.end {
            let stop = self.edge.0.min(self.end);
            if self.i < stop {
                acc = centre_run(&mut self.row, stop - self.i, acc, &mut f);
                self.i = stop;
            }
            let stop = self.edge.1.min(self.end);
            while self.i < stop {
                let i = self.i;
                self.i += 1;
                // The centre ray too: a test's row state expects every column.
                let _ = self.row.next_color();
                acc = f(acc, self.averaged(i));
            }
            let i = self.i;
            self.next_run(i);
        }
        acc
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.end - self.i) as usize;
        (n, Some(n))
    }
}

impl<'s, const N: usize, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> PixelRow
    for SpanRow<'_, '_, 's, N, S, T, Q, Sh, X>
{
    /// Every pixel as a [`Sample`]: a centre-ray pixel as the one-ray loop gives it
    /// (with its hit), an edge pixel with its average, `n²` rays and no hit.
    fn samples(mut self) -> impl Iterator<Item = Sample> {
        let rays = (self.steps.n * self.steps.n) as u32;
        core::iter::from_fn(move || {
            let i = self.i;
            if i >= self.end {
                return None;
            }
            let mut sample = self.row.next()?;
            self.i += 1;
            if self.is_edge(i) {
                sample.color = self.averaged(i);
                sample.hit = None;
                sample.rays = rays;
            }
            Some(sample)
        })
    }

    fn color_runs(mut self) -> ColorRuns<impl Iterator<Item = Rgb888>> {
        // Background before and after both the spans' union and the edge columns.
        let spans = self.row.spans();
        let first = spans
            .map_or(self.end, |(lo, _)| lo)
            .min(self.edge.0)
            .min(self.end)
            .max(self.i);
        let last = spans
            .map_or(first, |(_, hi)| hi)
            .max(
                self.bands
                    .iter()
                    .filter(|b| b.lo < b.hi)
                    .map(|b| b.hi)
                    .max()
                    .unwrap_or(first),
            )
            .min(self.end)
            .max(first);
        let before = first - self.i;
        self.row.skip_columns(before);
        self.i = first;
        let after = self.end - last;
        self.end = last;
        ColorRuns {
            background: self.row.background(),
            before,
            traced_len: last - first,
            traced: self,
            after,
        }
    }
}

/// `n` centre-ray pixels of `row` into `f`, out of line: the row loop's state stays
/// in registers here rather than beside the edge pixels' calls.
#[inline(never)]
fn centre_run<'s, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>, B>(
    row: &mut RowPixels<'_, 's, S, T, Q, Sh, X>,
    n: u32,
    init: B,
    f: &mut impl FnMut(B, Rgb888) -> B,
) -> B {
    let mut acc = init;
    for _ in 0..n {
        acc = f(acc, row.next_color());
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::edge_runs;
    use heapless::Vec;

    /// The merged runs hold exactly the columns of the union of the intervals, in
    /// increasing order, disjoint and not touching (empty intervals, touching ones,
    /// nested ones and reversed order included).
    #[test]
    fn edge_runs_are_the_union_of_the_intervals() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = |n: u32| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 33) as u32 % n
        };
        for _ in 0..2000 {
            let bands = 1 + next(6) as usize;
            let mut edges = std::vec::Vec::new();
            for _ in 0..bands {
                let mut four = [(0, 0); 4];
                for e in &mut four {
                    let a = next(40);
                    // About a quarter empty, some reversed (empty too).
                    *e = (a, a + next(12));
                    if next(4) == 0 {
                        *e = (e.1, e.0);
                    }
                }
                edges.push(four);
            }
            let mut runs: Vec<[(u32, u32); 4], 6> = Vec::new();
            let count = edge_runs(edges.iter().copied(), &mut runs);
            let got = &runs.as_flattened()[..count];
            for w in got.windows(2) {
                assert!(w[0].1 < w[1].0, "runs {got:?} overlap or touch");
            }
            for x in 0..60 {
                let want = edges.iter().flatten().any(|&(a, z)| a <= x && x < z);
                let have = got.iter().any(|&(a, z)| a <= x && x < z);
                assert_eq!(have, want, "column {x}: runs {got:?} of {edges:?}");
            }
        }
    }
}

//! The two-core band split of the RP2040 firmware: the frame is cut into bands of
//! `band_rows` rows (the last one shorter when `band_rows` does not divide the height),
//! and the cores take alternate bands, core 0 the even ones (0, 2, 4, …) and core 1 the
//! odd ones (1, 3, 5, …). The display receives the bands in index order, each core's
//! bands in the order that core traces them.
//!
//! Shared with `#[path]` by the firmware (`boards/rp2040/src/main.rs`) and the host
//! test `lab/tests/lab/rp2040_split.rs`, which proves that both cores' bands, sent in index
//! order, are the whole render's pixels.

use core::ops::Range;

/// The cores that trace.
pub const CORES: u32 = 2;

/// The firmware's band height: 240 rows make 12 bands, six per core, so both cores
/// trace as many rows per frame.
pub const BAND_ROWS: u32 = 20;

/// The core that traces band `band`: the bands alternate between the cores.
pub const fn core_of(band: u32) -> u32 {
    band % CORES
}

/// How many bands of `band_rows` rows (at least one row) cover `height` rows.
pub const fn band_count(height: u32, band_rows: u32) -> u32 {
    height.div_ceil(if band_rows == 0 { 1 } else { band_rows })
}

/// The rows of band `band` of `height` rows cut into bands of `band_rows` rows.
pub fn band_rows(band: u32, height: u32, band_rows: u32) -> Range<u32> {
    let band_rows = band_rows.max(1);
    let start = band.saturating_mul(band_rows).min(height);
    start..start.saturating_add(band_rows).min(height)
}

/// The bands core `core` traces, in the order it traces them (the order they go on the
/// wire): each band's index and rows.
pub fn core_bands(core: u32, height: u32, rows: u32) -> impl Iterator<Item = (u32, Range<u32>)> {
    (0..band_count(height, rows))
        .filter(move |&band| core_of(band) == core)
        .map(move |band| (band, band_rows(band, height, rows)))
}

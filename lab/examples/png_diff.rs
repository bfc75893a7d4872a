//! Compares two PNGs pixel by pixel (8-bit RGB), for the CI screenshot check.
//!
//! ```text
//! cargo run --features tools --example png_diff -- expected.png actual.png
//! ```
//!
//! Exit 0 when the sizes match and every pixel is identical; otherwise prints the size
//! mismatch or the number of differing pixels, the largest channel difference and the
//! first few, and exits 1. An
//! unreadable file is exit 2.

use std::process::ExitCode;

use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
use embedded_graphics_simulator::SimulatorDisplay;

/// How many differing pixels to list.
const SHOW: usize = 5;

fn load(path: &str) -> Result<SimulatorDisplay<Rgb888>, String> {
    SimulatorDisplay::load_png(path).map_err(|e| format!("{path}: {e}"))
}

/// The differing pixels of two equally sized displays: (position, expected, actual).
fn differences(a: &SimulatorDisplay<Rgb888>, b: &SimulatorDisplay<Rgb888>) -> Vec<(Point, Rgb888, Rgb888)> {
    a.bounding_box()
        .points()
        .filter_map(|p| {
            let (x, y) = (a.get_pixel(p), b.get_pixel(p));
            (x != y).then_some((p, x, y))
        })
        .collect()
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [expected, actual] = args.as_slice() else {
        eprintln!("usage: png_diff EXPECTED.png ACTUAL.png");
        return ExitCode::from(2);
    };
    let (a, b) = match (load(expected), load(actual)) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if a.size() != b.size() {
        eprintln!(
            "{expected} is {}x{}, {actual} is {}x{}",
            a.size().width,
            a.size().height,
            b.size().width,
            b.size().height
        );
        return ExitCode::from(1);
    }
    let diffs = differences(&a, &b);
    let total = a.size().width * a.size().height;
    if diffs.is_empty() {
        println!("{expected} = {actual}: all {total} pixels identical");
        return ExitCode::SUCCESS;
    }
    let largest = diffs
        .iter()
        .map(|(_, x, y)| {
            let d = |a: u8, b: u8| a.abs_diff(b);
            d(x.r(), y.r()).max(d(x.g(), y.g())).max(d(x.b(), y.b()))
        })
        .max()
        .unwrap_or(0);
    eprintln!(
        "{expected} != {actual}: {} of {total} pixels differ, by up to {largest} in a channel",
        diffs.len()
    );
    for (p, x, y) in diffs.iter().take(SHOW) {
        eprintln!("  ({}, {}): {:?} vs {:?}", p.x, p.y, x, y);
    }
    ExitCode::from(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_exactly_the_changed_pixels() {
        let mut a = SimulatorDisplay::<Rgb888>::new(Size::new(5, 4));
        let Ok(()) = a.clear(Rgb888::new(10, 20, 30));
        let mut b = a.clone();
        assert!(differences(&a, &b).is_empty());
        let Ok(()) = Pixel(Point::new(3, 2), Rgb888::new(10, 20, 31)).draw(&mut b);
        assert_eq!(
            differences(&a, &b),
            vec![(Point::new(3, 2), Rgb888::new(10, 20, 30), Rgb888::new(10, 20, 31))]
        );
    }
}

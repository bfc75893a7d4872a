//! Arbitrary bytes into the scene-file parser: it must never panic, and every
//! rejection must name a field or a line.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // A file that is not UTF-8 is rejected when it is read, before parsing; the
    // lossy decoding still exercises the parser with the replacement characters.
    let text = String::from_utf8_lossy(data);
    if let Err(e) = embedded_raytracer::scene_file::parse::<8, 2, 2, 3>(&text) {
        assert!(e.field.is_some() || e.line.is_some(), "{e:?} for {text:?}");
        assert!(!e.reason.is_empty());
    }
});

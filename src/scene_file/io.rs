//! Scene files from the file system: [`load`] reads a regular file of at most
//! [`MAX_FILE_SIZE`] bytes and parses it, and its errors carry the path.

use std::format;
use std::fs;
use std::io::Read;
use std::path::Path;
use std::string::String;
use std::vec::Vec;

use crate::scene_file::{parse, SceneFile, SceneFileError};

/// The largest scene file [`load`] reads, in bytes (1 MiB), and the longest text a
/// caller with untrusted text should pass to [`parse`].
///
/// Far above what a scene needs (`scenes/crowd.toml`, 64 spheres, is a few kilobytes),
/// it bounds what a hostile or mistaken file costs to read: the scan before the TOML
/// parser bounds the values it builds, not the length of the text.
pub const MAX_FILE_SIZE: u64 = 1 << 20;

/// Reads and parses a scene file; errors carry the path.
///
/// Only a regular file is read (a FIFO would block, a device like `/dev/zero` never
/// ends), and at most [`MAX_FILE_SIZE`] bytes of it.
pub fn load<const N: usize, const L: usize, const P: usize, const D: usize>(
    path: impl AsRef<Path>,
) -> Result<SceneFile<N, L, P, D>, SceneFileError> {
    let path = path.as_ref();
    let with_path = |mut e: SceneFileError| {
        e.path = Some(path.to_path_buf());
        e
    };
    let text = read_capped(path).map_err(|reason| {
        with_path(SceneFileError {
            path: None,
            field: None,
            line: None,
            reason,
        })
    })?;
    parse(&text).map_err(with_path)
}

/// The text of a regular file of at most [`MAX_FILE_SIZE`] bytes.
fn read_capped(path: &Path) -> Result<String, String> {
    let too_large =
        || format!("the file is larger than {MAX_FILE_SIZE} bytes (1 MiB), the limit for a scene file");
    // Look before opening: opening a FIFO would already block.
    let meta = fs::metadata(path).map_err(|e| format!("cannot read the file: {e}"))?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "a device, FIFO or socket"
        };
        return Err(format!(
            "not a regular file ({kind}): a scene must be a regular file"
        ));
    }
    if meta.len() > MAX_FILE_SIZE {
        return Err(too_large());
    }
    // The file may have grown since: read at most one byte past the limit.
    let mut bytes = Vec::new();
    fs::File::open(path)
        .and_then(|file| file.take(MAX_FILE_SIZE + 1).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot read the file: {e}"))?;
    if bytes.len() as u64 > MAX_FILE_SIZE {
        return Err(too_large());
    }
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "not UTF-8 text (invalid byte at offset {})",
            e.utf8_error().valid_up_to()
        )
    })
}

//! The scan before the TOML parser: a text that cannot be a scene of the capacities
//! asked for (nested too deep, too many values or table headers) is refused before the
//! parser builds a value for it.

use std::format;

use crate::scene_file::{SceneFileError, MAX_MOTIONS};

/// The deepest nesting of arrays and inline tables a scene file has a use for: an
/// inline array of tables whose values are arrays (`sphere = [{ center = [0, 0, 0] }]`).
const MAX_NESTING: usize = 3;

/// The most keys and separators, and the most table headers, the text of a scene of
/// `n` spheres, `l` lights, `p` planes and [`MAX_MOTIONS`] motions may have: twice what
/// that scene can hold, plus a margin.
///
/// Counted as the pre-check counts: keys (`=`) and separators (`,`), and table headers. A plane,
/// the largest object, has 8 keys and 4 arrays of 3 (8 separators, a trailing comma
/// each: 4 more), 20 in all; the camera 7 keys and 3 arrays, the top level 4 keys and 1
/// array. Twice, plus a margin: a file a little over a capacity still reaches the
/// parser, whose error names the count ("more than 2 spheres"); one far over it, which
/// could only be hostile, is refused without being parsed.
fn scene_bounds(n: usize, l: usize, p: usize) -> (usize, usize) {
    // Motions count as objects: a motion table is smaller than a plane's.
    let objects = n.saturating_add(l).saturating_add(p).saturating_add(MAX_MOTIONS);
    let entries = objects.saturating_mul(40).saturating_add(256);
    // One header per object and `[camera]`, twice, and a margin.
    let headers = objects.saturating_mul(2).saturating_add(16);
    (entries, headers)
}

/// Rejects, before the TOML parser builds anything, a text that cannot be a scene of
/// these capacities: nesting deeper than [`MAX_NESTING`], or more keys, values or
/// table headers than [`scene_bounds`] allows.
///
/// So the parser's memory is bounded by
/// that many small values whatever the file (1 MiB of `[[`, of `{`, or one array of half
/// a million numbers is refused here, at a scan's cost). The scan skips strings and
/// comments as TOML defines them; it need not be exact elsewhere, only never refuse a
/// valid scene: every count it makes is at least what the parser would see.
pub(super) fn precheck(text: &str, n: usize, l: usize, p: usize) -> Result<(), SceneFileError> {
    let (max_entries, max_headers) = scene_bounds(n, l, p);
    let (mut depth, mut entries, mut headers, mut line) = (0usize, 0usize, 0usize, 1usize);
    let mut line_start = true;
    let mut chars = text.chars().peekable();
    let too_many = |what: &str, line: usize| SceneFileError {
        path: None,
        field: None,
        line: Some(line),
        reason: format!(
            "more {what} than a scene of {n} spheres, {l} lights and {p} planes can hold \
             (checked before parsing, at most {})",
            if what == "table headers" {
                max_headers
            } else {
                max_entries
            }
        ),
    };
    while let Some(c) = chars.next() {
        match c {
            '\n' => {
                line += 1;
                line_start = true;
                continue;
            }
            ' ' | '\t' | '\r' => continue,
            '#' => {
                // A comment runs to the end of the line.
                while chars.peek().is_some_and(|&c| c != '\n') {
                    chars.next();
                }
                continue;
            }
            '"' | '\'' => {
                // A string: basic ones have escapes; either kind may be multi-line
                // (three quotes), which only the closing three quotes end.
                let triple = chars.peek() == Some(&c) && {
                    let mut ahead = chars.clone();
                    ahead.next();
                    ahead.peek() == Some(&c)
                };
                if triple {
                    chars.next();
                    chars.next();
                }
                let mut run = 0;
                while let Some(d) = chars.next() {
                    if d == '\n' {
                        line += 1;
                    }
                    if d == '\\' && c == '"' {
                        chars.next();
                        run = 0;
                        continue;
                    }
                    if d == c {
                        run += 1;
                        if !triple || run == 3 {
                            break;
                        }
                    } else {
                        run = 0;
                        if !triple && d == '\n' {
                            break;
                        }
                    }
                }
            }
            '[' if line_start && depth == 0 => {
                // A table header, `[name]` or `[[name]]`: one more table.
                headers += 1;
                if headers > max_headers {
                    return Err(too_many("table headers", line));
                }
                while chars.peek().is_some_and(|&c| c != '\n') {
                    chars.next();
                }
            }
            '[' | '{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Err(SceneFileError {
                        path: None,
                        field: None,
                        line: Some(line),
                        reason: format!(
                            "arrays and inline tables nested {depth} deep: no scene field nests deeper than {MAX_NESTING}"
                        ),
                    });
                }
            }
            ']' | '}' => depth = depth.saturating_sub(1),
            '=' | ',' => {
                entries += 1;
                if entries > max_entries {
                    return Err(too_many("keys and values", line));
                }
            }
            _ => {}
        }
        line_start = false;
    }
    Ok(())
}

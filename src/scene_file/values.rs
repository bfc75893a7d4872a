//! The strict value types the schema is written in: an array of exactly its length, a
//! number that its type holds, an array of tables capped at the scene type's capacity,
//! and a TOML date-time called a date-time where a number or an array belongs.

use std::fmt;
use std::format;
use std::marker::PhantomData;
use std::string::String;
use std::vec::Vec;

use serde::de::{self, Deserializer, IgnoredAny, MapAccess, SeqAccess, Unexpected, Visitor};
use serde::Deserialize;

/// An array of exactly `N` values: more or fewer is an error naming both counts.
pub(super) struct Exact<T, const N: usize>(pub(super) [T; N]);

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct ExactVisitor<T, const N: usize>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for ExactVisitor<T, N> {
            type Value = Exact<T, N>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an array of {N} values")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut values = Vec::with_capacity(N);
                while values.len() < N {
                    match seq.next_element()? {
                        Some(value) => values.push(value),
                        None => break,
                    }
                }
                // Count what is beyond the N-th value without reading it as a T.
                let mut found = values.len();
                while seq.next_element::<IgnoredAny>()?.is_some() {
                    found += 1;
                }
                match <[T; N]>::try_from(values) {
                    Ok(array) if found == N => Ok(Exact(array)),
                    _ => Err(de::Error::custom(format_args!(
                        "expected {N} values, found {found}"
                    ))),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
                Err(date_or_map(map, &self))
            }
        }
        d.deserialize_any(ExactVisitor(PhantomData))
    }
}

/// A number that `f32` holds: an integer, or a float whose magnitude is neither above
/// `f32::MAX` nor so small that it would round to 0 (`nan` and `inf` pass through, for
/// the camera and sphere checks to report as not finite).
pub(super) struct F32(pub(super) f32);

impl<'de> Deserialize<'de> for F32 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct F32Visitor;
        impl<'de> Visitor<'de> for F32Visitor {
            type Value = F32;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<F32, E> {
                let single = v as f32;
                if v.is_finite() && single.is_infinite() {
                    return Err(E::custom(format_args!(
                        "{v:e} is outside the f32 range (largest magnitude {:e})",
                        f32::MAX
                    )));
                }
                if v != 0.0 && single == 0.0 {
                    return Err(E::custom(format_args!(
                        "{v:e} is outside the f32 range (it rounds to 0; smallest magnitude {:e})",
                        f32::from_bits(1)
                    )));
                }
                Ok(F32(single))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<F32, E> {
                Ok(F32(v as f32))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<F32, E> {
                Ok(F32(v as f32))
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<F32, A::Error> {
                Err(date_or_map(map, &self))
            }
        }
        d.deserialize_any(F32Visitor)
    }
}

/// An unsigned integer field (`u8` colour channel, `u32` size).
pub(super) struct Int<T>(pub(super) T);

impl<'de, T: TryFrom<u64> + Bounded> Deserialize<'de> for Int<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct IntVisitor<T>(PhantomData<T>);
        impl<'de, T: TryFrom<u64> + Bounded> Visitor<'de> for IntVisitor<T> {
            type Value = Int<T>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an integer from 0 to {}", T::MAX)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Int<T>, E> {
                T::try_from(v)
                    .map(Int)
                    .map_err(|_| E::invalid_value(Unexpected::Unsigned(v), &self))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Int<T>, E> {
                match u64::try_from(v) {
                    Ok(v) => self.visit_u64(v),
                    Err(_) => Err(E::invalid_value(Unexpected::Signed(v), &self)),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Int<T>, A::Error> {
                Err(date_or_map(map, &self))
            }
        }
        d.deserialize_any(IntVisitor(PhantomData))
    }
}

/// The largest value of an [`Int`] field, for its messages.
pub(super) trait Bounded {
    const MAX: u64;
}

impl Bounded for u8 {
    const MAX: u64 = u8::MAX as u64;
}

impl Bounded for u32 {
    const MAX: u64 = u32::MAX as u64;
}

/// `max_depth`: any integer `≥ 0`, held saturated at 255 so that every value above
/// [`MAX_DEPTH`](crate::MAX_DEPTH) gets the settings check's "at most" message.
pub(super) struct Depth(pub(super) u8);

impl<'de> Deserialize<'de> for Depth {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct DepthVisitor;
        impl<'de> Visitor<'de> for DepthVisitor {
            type Value = Depth;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an integer from 0 to {}", crate::MAX_DEPTH)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Depth, E> {
                Ok(Depth(u8::try_from(v).unwrap_or(u8::MAX)))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Depth, E> {
                match u64::try_from(v) {
                    Ok(v) => self.visit_u64(v),
                    Err(_) => Err(E::invalid_value(Unexpected::Signed(v), &self)),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Depth, A::Error> {
                Err(date_or_map(map, &self))
            }
        }
        d.deserialize_any(DepthVisitor)
    }
}

/// A TOML date-time where `what` is expected: toml hands it to a visitor as a map,
/// which serde would report as "invalid type: map".
fn date_or_map<'de, A: MapAccess<'de>>(map: A, what: &dyn de::Expected) -> A::Error {
    match toml::value::Datetime::deserialize(de::value::MapAccessDeserializer::new(map)) {
        Ok(date) => de::Error::custom(format_args!("invalid type: date-time {date}, expected {what}")),
        Err(_) => de::Error::invalid_type(Unexpected::Map, what),
    }
}

/// The noun an array of tables is counted in, for the too-many message.
pub(super) trait Noun {
    const NOUN: &'static str;
}

/// `count` and the noun, singular for 1.
pub(super) fn count_of(count: usize, noun: &str) -> String {
    if count == 1 {
        format!("1 {noun}")
    } else {
        format!("{count} {noun}s")
    }
}

/// An array of tables (`[[sphere]]`, `[[light]]`, `[[plane]]`), refused as soon as it
/// has more than `N` entries: entry `N + 1` is skipped unread, nothing after it is
/// looked at.
pub(super) fn capped<'de, D: Deserializer<'de>, T: Deserialize<'de> + Noun, const N: usize>(
    d: D,
) -> Result<Vec<T>, D::Error> {
    struct Capped<T, const N: usize>(PhantomData<T>);
    impl<'de, T: Deserialize<'de> + Noun, const N: usize> Visitor<'de> for Capped<T, N> {
        type Value = Vec<T>;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "an array of [[{}]] tables", T::NOUN)
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
            let mut entries = Vec::new();
            while entries.len() < N {
                match seq.next_element()? {
                    Some(entry) => entries.push(entry),
                    None => return Ok(entries),
                }
            }
            if seq.next_element::<IgnoredAny>()?.is_some() {
                let verb = if N == 1 { "is" } else { "are" };
                return Err(de::Error::custom(format_args!(
                    "more than {}: at most {N} {verb} supported",
                    count_of(N, T::NOUN)
                )));
            }
            Ok(entries)
        }
    }
    d.deserialize_seq(Capped::<T, N>(PhantomData))
}

//! [`Pair`]: a point `[x, y]` in map metres as a file writes it, exactly two numbers (the
//! route's waypoints, `map.origin_m`, a science target's position).

use serde::Deserialize;

/// Exactly two numbers, `[x, y]`. serde's `[f64; 2]` reads the first two numbers of a longer
/// array and drops the rest, so a 3-D waypoint `[x, y, z]` passed with its altitude ignored.
#[derive(Debug, Clone, Copy, PartialEq, schemars::JsonSchema)]
#[schemars(transparent)]
pub(crate) struct Pair(pub(crate) [f64; 2]);

impl<'de> Deserialize<'de> for Pair {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        const EXPECTED: &str = "[x, y]: exactly two numbers (map metres, no altitude)";
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Pair;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(EXPECTED)
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Pair, A::Error> {
                use serde::de::Error;
                let x = seq.next_element::<f64>()?;
                let y = seq.next_element::<f64>()?;
                let (Some(x), Some(y)) = (x, y) else {
                    return Err(A::Error::invalid_length(
                        usize::from(x.is_some()),
                        &EXPECTED,
                    ));
                };
                let mut len = 2;
                while seq.next_element::<serde::de::IgnoredAny>()?.is_some() {
                    len += 1;
                }
                if len == 2 {
                    Ok(Pair([x, y]))
                } else {
                    Err(A::Error::invalid_length(len, &EXPECTED))
                }
            }
        }
        deserializer.deserialize_seq(Visitor)
    }
}

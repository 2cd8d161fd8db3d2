//! The scene file as written (TOML): its sections and keys, read strictly (an unknown key is
//! refused) into plain values that [`super::validate`] checks. A list of values may be given
//! as a number, a list or an evenly spaced range ([`Values`]).

use std::fmt;
use std::path::PathBuf;

use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};

use super::MAX_CASES;

/// A number, a list of numbers or an evenly spaced range `{ from, to, count }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Values(pub Vec<f64>);

impl<'de> Deserialize<'de> for Values {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ValuesVisitor)
    }
}

struct ValuesVisitor;

impl<'de> Visitor<'de> for ValuesVisitor {
    type Value = Values;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number, a list of numbers, or a table { from = A, to = B, count = N }")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Values, E> {
        Ok(Values(vec![v]))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Values, E> {
        Ok(Values(vec![v as f64]))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Values, E> {
        Ok(Values(vec![v as f64]))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Values, A::Error> {
        let mut out = Vec::new();
        while let Some(v) = seq.next_element::<f64>()? {
            if out.len() >= MAX_CASES {
                return Err(de::Error::custom(format!(
                    "more than {MAX_CASES} values in one list"
                )));
            }
            out.push(v);
        }
        if out.is_empty() {
            return Err(de::Error::custom("an empty list: give at least one value"));
        }
        Ok(Values(out))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Values, A::Error> {
        let (mut from, mut to, mut count) = (None, None, None);
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "from" => from = Some(map.next_value::<f64>()?),
                "to" => to = Some(map.next_value::<f64>()?),
                "count" => count = Some(map.next_value::<i64>()?),
                other => return Err(de::Error::unknown_field(other, &["from", "to", "count"])),
            }
        }
        let from = from.ok_or_else(|| de::Error::missing_field("from"))?;
        let to = to.ok_or_else(|| de::Error::missing_field("to"))?;
        let count = count.ok_or_else(|| de::Error::missing_field("count"))?;
        if count < 1 || count as usize > MAX_CASES || (count == 1 && from != to) {
            return Err(de::Error::custom(format!(
                "count = {count}: must be an integer in [2, {MAX_CASES}] (1 only when from = to)"
            )));
        }
        let n = count as usize;
        let values = (0..n)
            .map(|i| {
                if i + 1 == n {
                    to
                } else {
                    from + (to - from) * i as f64 / (n - 1).max(1) as f64
                }
            })
            .collect();
        Ok(Values(values))
    }
}
/// `yield_pressure`: a pressure (Pa), or a word (`"catalogue"`: the limiting pressure of the
/// bodies' catalogue materials).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(super) enum YieldPressureFile {
    /// `p_y` in Pa.
    Pascal(f64),
    /// A word naming where `p_y` comes from.
    Named(String),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneFile {
    pub(super) name: Option<String>,
    pub(super) description: Option<String>,
    pub(super) friction: f64,
    pub(super) tol: Option<f64>,
    pub(super) e_n: Option<f64>,
    pub(super) relaxation_time: Option<f64>,
    pub(super) yield_pressure: Option<YieldPressureFile>,
    pub(super) sphere: SphereFile,
    pub(super) target: TargetFile,
    pub(super) cases: CasesFile,
    pub(super) measured: Option<MeasuredFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SphereFile {
    pub(super) material: Option<String>,
    pub(super) youngs_modulus: Option<f64>,
    pub(super) poisson_ratio: Option<f64>,
    pub(super) density: Option<f64>,
    pub(super) mass: Option<f64>,
    pub(super) radius: f64,
    pub(super) inner_radius: Option<f64>,
    pub(super) kappa: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TargetFile {
    pub(super) kind: String,
    pub(super) material: Option<String>,
    pub(super) youngs_modulus: Option<f64>,
    pub(super) poisson_ratio: Option<f64>,
    pub(super) density: Option<f64>,
    pub(super) mass: Option<f64>,
    pub(super) radius: Option<f64>,
    pub(super) inner_radius: Option<f64>,
    pub(super) kappa: Option<f64>,
    pub(super) v_x: Option<f64>,
    pub(super) v_z: Option<f64>,
    pub(super) omega: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CasesFile {
    pub(super) kind: String,
    pub(super) speed: Option<f64>,
    pub(super) angles_deg: Option<Values>,
    pub(super) normal_speed: Option<f64>,
    pub(super) tangential_speed: Option<Values>,
    pub(super) omega0: Option<Values>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeasuredFile {
    pub(super) file: PathBuf,
    pub(super) source: String,
}

//! A TOML table walker that knows where it is.
//!
//! serde's derive gives poor messages for "a number or a table" fields and cannot say which
//! keys were never read, so the scenario is read by hand through this walker: every getter
//! takes the key, knows the dotted path of its table, removes the key it read, and every
//! error names the key, the value found and what is allowed. `finish` reports the keys that
//! nobody asked for, with the closest known key as a hint.

use super::error::ScenarioError;
use std::sync::LazyLock;
use toml::{Table, Value};

/// The commented default scenario, as `touchdown scenario` prints it: the one place that
/// gives every key of its tables its default (the reader takes a missing key's value from
/// here, at the same path).
pub const DEFAULT_TOML: &str = include_str!("default.toml");

static DEFAULTS: LazyLock<Table> =
    LazyLock::new(|| DEFAULT_TOML.parse().expect("default.toml is TOML"));

/// One table of the scenario file, with the dotted path that leads to it and the defaults
/// of its keys.
pub(crate) struct Reader {
    path: String,
    table: Table,
    defaults: Table,
    known: Vec<&'static str>,
}

/// Declares a table of the scenario file once: its struct, every key a documented field,
/// and the function that reads it, each key under its field's name (`$key` names it in the
/// field's reading expression, which sees the fields read before it). A key's default is
/// default.toml's at the same path, or one the expression gives (`Reader::or`).
macro_rules! table {
    (
        $(#[$meta:meta])*
        pub struct $name:ident;
        $(#[$read_meta:meta])*
        fn $read:ident($r:ident $(, $arg:ident: $arg_ty:ty)*) with $key:ident {
            $( $(#[$field_meta:meta])* $field:ident: $ty:ty = $value:expr ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $( $(#[$field_meta])* pub $field: $ty, )*
        }

        $(#[$read_meta])*
        pub(super) fn $read(
            $r: &mut $crate::scenario::reader::Reader $(, $arg: $arg_ty)*
        ) -> Result<$name, $crate::scenario::error::ScenarioError> {
            $(
                #[allow(unused_mut)]
                let mut $field: $ty = {
                    #[allow(unused_variables)]
                    let $key: &'static str = stringify!($field);
                    $value
                };
            )*
            $r.finish()?;
            Ok($name { $($field),* })
        }
    };
}
pub(crate) use table;

impl Reader {
    /// The top level of a scenario file, its defaults those of default.toml.
    pub(crate) fn top(table: Table) -> Self {
        Reader {
            defaults: DEFAULTS.clone(),
            ..Reader::new("", table)
        }
    }

    /// A table without defaults (a distribution, a thruster).
    pub(crate) fn new(path: &str, table: Table) -> Self {
        Reader {
            path: path.to_string(),
            table,
            defaults: Table::new(),
            known: Vec::new(),
        }
    }

    /// The dotted path of `key` in this table.
    pub(crate) fn key_path(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{}", self.path, key)
        }
    }

    pub(crate) fn error(&self, key: &str, value: &Value, allowed: &str) -> ScenarioError {
        ScenarioError::Invalid {
            key: self.key_path(key),
            value: show(value),
            allowed: allowed.to_string(),
        }
    }

    /// Takes `key` out of the file's table, remembering that it is a known key.
    pub(crate) fn take(&mut self, key: &'static str) -> Option<Value> {
        self.known.push(key);
        self.table.remove(key)
    }

    /// Whether the file gives `key`.
    pub(crate) fn has(&self, key: &str) -> bool {
        self.table.contains_key(key)
    }

    /// `read` of `key` where the file gives it, else `None` (a key without a default).
    pub(crate) fn given<T>(
        &mut self,
        key: &'static str,
        read: impl FnOnce(&mut Self) -> Result<T, ScenarioError>,
    ) -> Result<Option<T>, ScenarioError> {
        if self.has(key) {
            read(self).map(Some)
        } else {
            self.known.push(key);
            Ok(None)
        }
    }

    /// Gives `key` the default `value` where default.toml gives it none.
    pub(crate) fn or(&mut self, key: &str, value: impl Into<Value>) -> &mut Self {
        self.defaults.entry(key).or_insert_with(|| value.into());
        self
    }

    /// The file's value at `key`, else its default.
    pub(crate) fn value(&mut self, key: &'static str) -> Result<Value, ScenarioError> {
        self.get(key, |_, v| Ok(v.clone()), |_, v| Ok(v.clone()))
    }

    /// The file's value at `key` read by `read`, else the default read by `default`, else
    /// an error (a key with no default that the file leaves out).
    fn get<T>(
        &mut self,
        key: &'static str,
        read: impl FnOnce(&Self, &Value) -> Result<T, ScenarioError>,
        default: impl FnOnce(&Self, &Value) -> Result<T, ScenarioError>,
    ) -> Result<T, ScenarioError> {
        match self.take(key) {
            Some(v) => read(self, &v),
            None => match self.defaults.get(key) {
                Some(v) => default(self, v),
                None => Err(ScenarioError::Invalid {
                    key: self.key_path(key),
                    value: "nothing".into(),
                    allowed: "a value".into(),
                }),
            },
        }
    }

    /// A finite number (integers are accepted where a float is wanted).
    pub(crate) fn f64(&mut self, key: &'static str) -> Result<f64, ScenarioError> {
        self.get(key, |r, v| r.number(key, v), |r, v| r.number(key, v))
    }

    pub(crate) fn number(&self, key: &str, v: &Value) -> Result<f64, ScenarioError> {
        let x = match v {
            Value::Float(x) => *x,
            Value::Integer(i) => *i as f64,
            _ => return Err(self.error(key, v, "a number")),
        };
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.error(key, v, "a finite number (not nan or inf)"))
        }
    }

    /// A number checked by `ok`, whose failure message is `allowed` (a default is not
    /// checked: `ok` may depend on keys the file gives).
    pub(crate) fn f64_where(
        &mut self,
        key: &'static str,
        allowed: &str,
        ok: impl Fn(f64) -> bool,
    ) -> Result<f64, ScenarioError> {
        let checked = |r: &Self, v: &Value| {
            let x = r.number(key, v)?;
            if ok(x) {
                Ok(x)
            } else {
                Err(r.error(key, v, allowed))
            }
        };
        self.get(key, checked, |r, v| r.number(key, v))
    }

    pub(crate) fn positive(&mut self, key: &'static str) -> Result<f64, ScenarioError> {
        self.f64_where(key, "a number greater than 0", |x| x > 0.0)
    }

    pub(crate) fn non_negative(&mut self, key: &'static str) -> Result<f64, ScenarioError> {
        self.f64_where(key, "a number of at least 0", |x| x >= 0.0)
    }

    /// An integer in `min..=max`.
    pub(crate) fn integer<T: TryFrom<i64>>(
        &mut self,
        key: &'static str,
        min: i64,
        max: i64,
    ) -> Result<T, ScenarioError> {
        let read = |r: &Self, v: &Value| {
            match v {
                Value::Integer(i) if (min..=max).contains(i) => T::try_from(*i).ok(),
                _ => None,
            }
            .ok_or_else(|| r.error(key, v, &format!("a whole number from {min} to {max}")))
        };
        self.get(key, read, read)
    }

    pub(crate) fn bool(&mut self, key: &'static str) -> Result<bool, ScenarioError> {
        let read = |r: &Self, v: &Value| match v {
            Value::Boolean(b) => Ok(*b),
            _ => Err(r.error(key, v, "true or false")),
        };
        self.get(key, read, read)
    }

    /// One of the given words, as the value it stands for.
    pub(crate) fn word<T: Copy>(
        &mut self,
        key: &'static str,
        words: &[(&'static str, T)],
    ) -> Result<T, ScenarioError> {
        let read = |r: &Self, v: &Value| r.word_of(key, v, words);
        self.get(key, read, read)
    }

    /// `v`, one of the given words, as the value it stands for.
    fn word_of<T: Copy>(
        &self,
        key: &str,
        v: &Value,
        words: &[(&'static str, T)],
    ) -> Result<T, ScenarioError> {
        if let Value::String(s) = v
            && let Some((_, w)) = words.iter().find(|(w, _)| w == s)
        {
            return Ok(*w);
        }
        let list: Vec<String> = words.iter().map(|(w, _)| format!("\"{w}\"")).collect();
        Err(self.error(key, v, &format!("one of {}", list.join(", "))))
    }

    /// A vector of three finite numbers.
    pub(crate) fn vec3(&self, key: &str, v: &Value) -> Result<[f64; 3], ScenarioError> {
        let allowed = "an array of three numbers [x, y, z]";
        match v {
            Value::Array(a) if a.len() == 3 => {
                let mut out = [0.0; 3];
                for (o, x) in out.iter_mut().zip(a) {
                    *o = self
                        .number(key, x)
                        .map_err(|_| self.error(key, v, allowed))?;
                }
                Ok(out)
            }
            _ => Err(self.error(key, v, allowed)),
        }
    }

    /// A sub-table as a reader of its own (its defaults those at its path), or `None` when
    /// neither the file nor the defaults have it.
    fn table(&mut self, key: &'static str) -> Result<Option<Reader>, ScenarioError> {
        let defaults = match self.defaults.get(key) {
            Some(Value::Table(d)) => Some(d.clone()),
            _ => None,
        };
        let table = match self.take(key) {
            None if defaults.is_none() => return Ok(None),
            None => Table::new(),
            Some(Value::Table(t)) => t,
            Some(v) => return Err(self.error(key, &v, "a table")),
        };
        Ok(Some(Reader {
            defaults: defaults.unwrap_or_default(),
            ..Reader::new(&self.key_path(key), table)
        }))
    }

    /// The sub-table `key` read by `read`, or `None` when neither the file nor the defaults
    /// have it.
    pub(crate) fn optional<T>(
        &mut self,
        key: &'static str,
        read: impl FnOnce(&mut Reader) -> Result<T, ScenarioError>,
    ) -> Result<Option<T>, ScenarioError> {
        self.table(key)?.map(|mut t| read(&mut t)).transpose()
    }

    /// The sub-table `key` read by `read`: where the file leaves it out, its defaults.
    pub(crate) fn section<T>(
        &mut self,
        key: &'static str,
        read: impl FnOnce(&mut Reader) -> Result<T, ScenarioError>,
    ) -> Result<T, ScenarioError> {
        let mut t = self
            .table(key)?
            .unwrap_or_else(|| Reader::new(&self.key_path(key), Table::new()));
        read(&mut t)
    }

    /// Fails on the first key that no getter asked for.
    pub(crate) fn finish(&mut self) -> Result<(), ScenarioError> {
        if let Some((key, _)) = self.table.iter().next() {
            let hint = closest(key, &self.known)
                .map(|k| format!(" (did you mean `{}`?)", k))
                .unwrap_or_default();
            let mut known = self.known.clone();
            known.sort_unstable();
            known.dedup();
            return Err(ScenarioError::UnknownKey {
                key: self.key_path(key),
                hint,
                known: known.join(", "),
            });
        }
        Ok(())
    }
}

/// A value as it would be written in TOML, kept short.
pub(crate) fn show(v: &Value) -> String {
    let s = match v {
        Value::String(s) => format!("{s:?}"),
        Value::Float(x) if x.is_nan() => "nan".to_string(),
        _ => v.to_string(),
    };
    if s.chars().count() > 60 {
        let cut: String = s.chars().take(57).collect();
        format!("{cut}...")
    } else {
        s
    }
}

/// The known key closest to `key` by edit distance, if it is close enough to be a typo.
fn closest(key: &str, known: &[&'static str]) -> Option<&'static str> {
    known
        .iter()
        .map(|k| (edit_distance(key, k), *k))
        .filter(|(d, k)| *d <= 2.max(k.len() / 4))
        .min()
        .map(|(_, k)| k)
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = if ca == *cb {
                prev
            } else {
                1 + prev.min(cur).min(row[j])
            };
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("mass_kg", "mass_kg"), 0);
        assert_eq!(edit_distance("mas_kg", "mass_kg"), 1);
        assert_eq!(edit_distance("mass_gk", "mass_kg"), 2);
        assert_eq!(
            closest("mas_kg", &["mass_kg", "inertia_kg_m2"]),
            Some("mass_kg")
        );
        assert_eq!(closest("colour", &["mass_kg"]), None);
    }
}

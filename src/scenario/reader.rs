//! A TOML table walker that knows where it is.
//!
//! serde's derive gives poor messages for "a number or a table" fields and cannot say which
//! keys were never read, so the scenario is read by hand through this walker: every getter
//! takes the key, knows the dotted path of its table, removes the key it read, and every
//! error names the key, the value found and what is allowed. `finish` reports the keys that
//! nobody asked for, with the closest known key as a hint.

use super::error::ScenarioError;
use toml::{Table, Value};

/// One table of the scenario file, with the dotted path that leads to it.
pub(crate) struct Reader {
    path: String,
    table: Table,
    known: Vec<&'static str>,
}

impl Reader {
    pub(crate) fn new(path: &str, table: Table) -> Self {
        Reader {
            path: path.to_string(),
            table,
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

    /// Takes `key` out of the table, remembering that it is a known key.
    pub(crate) fn take(&mut self, key: &'static str) -> Option<Value> {
        self.known.push(key);
        self.table.remove(key)
    }

    pub(crate) fn has(&self, key: &str) -> bool {
        self.table.contains_key(key)
    }

    /// A finite number (integers are accepted where a float is wanted).
    pub(crate) fn f64(&mut self, key: &'static str, default: f64) -> Result<f64, ScenarioError> {
        match self.take(key) {
            None => Ok(default),
            Some(v) => self.number(key, &v),
        }
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

    /// A number checked by `ok`, whose failure message is `allowed`.
    pub(crate) fn f64_where(
        &mut self,
        key: &'static str,
        default: f64,
        allowed: &str,
        ok: impl Fn(f64) -> bool,
    ) -> Result<f64, ScenarioError> {
        match self.take(key) {
            None => Ok(default),
            Some(v) => {
                let x = self.number(key, &v)?;
                if ok(x) {
                    Ok(x)
                } else {
                    Err(self.error(key, &v, allowed))
                }
            }
        }
    }

    pub(crate) fn positive(
        &mut self,
        key: &'static str,
        default: f64,
    ) -> Result<f64, ScenarioError> {
        self.f64_where(key, default, "a number greater than 0", |x| x > 0.0)
    }

    pub(crate) fn non_negative(
        &mut self,
        key: &'static str,
        default: f64,
    ) -> Result<f64, ScenarioError> {
        self.f64_where(key, default, "a number of at least 0", |x| x >= 0.0)
    }

    /// An integer in `min..=max`.
    pub(crate) fn integer(
        &mut self,
        key: &'static str,
        default: i64,
        min: i64,
        max: i64,
    ) -> Result<i64, ScenarioError> {
        match self.take(key) {
            None => Ok(default),
            Some(v) => match v {
                Value::Integer(i) if (min..=max).contains(&i) => Ok(i),
                _ => Err(self.error(key, &v, &format!("a whole number from {min} to {max}"))),
            },
        }
    }

    pub(crate) fn bool(&mut self, key: &'static str, default: bool) -> Result<bool, ScenarioError> {
        match self.take(key) {
            None => Ok(default),
            Some(Value::Boolean(b)) => Ok(b),
            Some(v) => Err(self.error(key, &v, "true or false")),
        }
    }

    /// One of the given words.
    pub(crate) fn word(
        &mut self,
        key: &'static str,
        default: &'static str,
        words: &[&'static str],
    ) -> Result<&'static str, ScenarioError> {
        match self.take(key) {
            None => Ok(default),
            Some(v) => {
                if let Value::String(s) = &v
                    && let Some(w) = words.iter().find(|w| *w == s)
                {
                    return Ok(w);
                }
                let list: Vec<String> = words.iter().map(|w| format!("\"{w}\"")).collect();
                Err(self.error(key, &v, &format!("one of {}", list.join(", "))))
            }
        }
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

    /// A sub-table as a reader of its own, or `None` when absent.
    pub(crate) fn table(&mut self, key: &'static str) -> Result<Option<Reader>, ScenarioError> {
        match self.take(key) {
            None => Ok(None),
            Some(Value::Table(t)) => Ok(Some(Reader::new(&self.key_path(key), t))),
            Some(v) => Err(self.error(key, &v, "a table")),
        }
    }

    /// Fails on the first key that no getter asked for.
    pub(crate) fn finish(self) -> Result<(), ScenarioError> {
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

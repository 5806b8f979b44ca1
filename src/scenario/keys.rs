//! A scenario's keys by their dotted names (`lander.mass_kg`, `thrusters.2.max_thrust_n`):
//! the tables of a scenario file joined by dots, a list of tables (`[[thrusters]]`) indexed
//! from 0. `study --vary` sets a key by it, and the Python package reads and sets any.

use anyhow::bail;

/// The table of `table` that holds `key`'s last name (made where missing); a name of a
/// list of tables (`[[thrusters]]`) is followed by the index of one, from 0
/// (`thrusters.2.max_thrust_n`).
pub fn parent_table<'t>(
    table: &'t mut toml::Table,
    key: &str,
) -> anyhow::Result<&'t mut toml::Table> {
    let names: Vec<&str> = key.split('.').collect();
    let parents = names.len() - 1;
    let mut at = table;
    let mut i = 0;
    while i < parents {
        let name = names[i];
        let index = names[i + 1..parents]
            .first()
            .filter(|n| n.bytes().all(|b| b.is_ascii_digit()));
        if index.is_some() && !at.contains_key(name) {
            bail!("the scenario has no [[{name}]] to take one of by its index");
        }
        let entry = at
            .entry(name.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        at = match entry {
            toml::Value::Table(t) => t,
            toml::Value::Array(items) => {
                let n = items.len();
                let Some(j) = index.and_then(|j| j.parse::<usize>().ok()) else {
                    bail!(
                        "`{name}` is a list of {n} tables in the scenario: name one by its \
                         index from 0 ({name}.0.KEY to {name}.{}.KEY)",
                        n.saturating_sub(1)
                    )
                };
                i += 1;
                match items.get_mut(j) {
                    Some(toml::Value::Table(t)) => t,
                    Some(_) => bail!("`{name}` is not a list of tables"),
                    None => bail!(
                        "the scenario has {n} [[{name}]] (indices 0 to {}), no index {j}",
                        n.saturating_sub(1)
                    ),
                }
            }
            _ => bail!(
                "`{}` is a value in the scenario, not a table of keys",
                names[..=i].join(".")
            ),
        };
        i += 1;
    }
    Ok(at)
}

/// The value of `key` in `table` (a table, a list or a value), or none where the scenario
/// does not give it (its default then holds).
#[must_use]
pub fn get<'t>(table: &'t toml::Table, key: &str) -> Option<&'t toml::Value> {
    let mut names = key.split('.');
    let mut at = table.get(names.next()?)?;
    for name in names {
        at = match at {
            toml::Value::Table(t) => t.get(name)?,
            toml::Value::Array(items) => items.get(name.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    Some(at)
}

/// `table` with `key` set to `value` (its tables made where missing).
pub fn set(table: &mut toml::Table, key: &str, value: toml::Value) -> anyhow::Result<()> {
    if key.is_empty() || key.split('.').any(str::is_empty) {
        bail!("`{key}` is not a key of the scenario (names joined by dots: lander.mass_kg)");
    }
    let leaf = key.rsplit('.').next().unwrap_or(key);
    parent_table(table, key)?.insert(leaf.to_string(), value);
    Ok(())
}

//! Lists read whole. A config's lists have a fixed length (a `[min, max]` range, a position's
//! `[x, y]`, the six home joints), and toml's reader of a text fills such a list from its first
//! elements and ignores the rest: `fixture_friction = [0.3, 1.2, 9.0]` was read as
//! `[0.3, 1.2]`, `base_radius = [0.25, 0.4, "junk", {a = 1}]` as `[0.25, 0.4]`. So a config is
//! first read from its parsed document by [`check_lists`], whose reader refuses a list with
//! elements left over or missing, naming the field, the list and the length its type has: one
//! rule for every list of every table, whatever its field. Everything else (types, unknown
//! keys, values) is left to the typed reader that follows, whose messages cite the line.

use serde::de::{self, DeserializeOwned, DeserializeSeed, IntoDeserializer, Visitor};

use crate::config::error::ConfigError;

/// Refuses a list of `doc` whose length is not the one its field of `T` holds, naming the field
/// (`task.place.fixture_friction`), the list as written and both lengths. A document that does
/// not read as `T` for another reason passes: the typed reader refuses it.
pub fn check_lists<T: DeserializeOwned>(doc: &toml::Table) -> Result<(), ConfigError> {
    let root = toml::Value::Table(doc.clone());
    let Err(e) = T::deserialize(Reader {
        value: &root,
        field: String::new(),
    }) else {
        return Ok(());
    };
    let Some(length) = e.length else {
        return Ok(());
    };
    let field = e.field.unwrap_or_default();
    let list = value_at(&root, &field);
    let mixed = list.and_then(|v| v.as_array()).and_then(|a| mixed_types(a));
    let given = match length.given {
        1 => "1 element".to_string(),
        n => format!("{n} elements"),
    };
    let rule = match (length.expected, mixed) {
        (Some(n), None) => format!("has {given}: it must hold exactly {n}"),
        (Some(n), Some(types)) => {
            format!("has {given} and mixes {types}: it must hold exactly {n}, of one type")
        }
        (None, _) => format!("has {given}: {}", e.message),
    };
    Err(ConfigError::Invalid {
        field,
        value: list.map_or_else(String::new, |v| {
            fairgrasp_types::text::excerpt(&v.to_string(), fairgrasp_types::text::MAX_QUOTED_CHARS)
        }),
        rule: rule.into(),
    })
}

/// The value at a dotted `field` (`a.b[1].c`) of `root`.
fn value_at<'a>(root: &'a toml::Value, field: &str) -> Option<&'a toml::Value> {
    let mut value = root;
    for part in field.split('.').filter(|p| !p.is_empty()) {
        let (key, indices) = part.split_once('[').unwrap_or((part, ""));
        value = value.get(key)?;
        for index in indices.split('[').filter(|i| !i.is_empty()) {
            value = value.get(index.trim_end_matches(']').parse::<usize>().ok()?)?;
        }
    }
    Some(value)
}

/// The types a list mixes (`a number, a string and a table`), if it holds more than one
/// (integers and floats are both numbers).
fn mixed_types(list: &[toml::Value]) -> Option<String> {
    let mut kinds: Vec<&str> = Vec::new();
    for v in list {
        let kind = match v {
            toml::Value::Integer(_) | toml::Value::Float(_) => "a number",
            toml::Value::String(_) => "a string",
            toml::Value::Boolean(_) => "a boolean",
            toml::Value::Datetime(_) => "a date",
            toml::Value::Array(_) => "a list",
            toml::Value::Table(_) => "a table",
        };
        if !kinds.contains(&kind) {
            kinds.push(kind);
        }
    }
    match kinds.as_slice() {
        [] | [_] => None,
        [init @ .., last] => Some(format!("{} and {last}", init.join(", "))),
    }
}

/// A list's length that its field cannot hold.
#[derive(Debug, Clone, Copy)]
struct Length {
    /// Elements written.
    given: usize,
    /// Elements the field holds, when the list has more (it read this many; else serde's
    /// message says how many it wanted).
    expected: Option<usize>,
}

/// Why a document did not read: a list's length (with the field), or anything else.
#[derive(Debug)]
struct ReadError {
    field: Option<String>,
    message: String,
    length: Option<Length>,
}

impl ReadError {
    /// The error, said of `field` unless a field inside it was named already.
    fn at(mut self, field: &str) -> Self {
        if self.field.is_none() {
            self.field = Some(field.to_string());
        }
        self
    }
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ReadError {}

impl de::Error for ReadError {
    fn custom<M: std::fmt::Display>(message: M) -> Self {
        ReadError {
            field: None,
            message: message.to_string(),
            length: None,
        }
    }
}

/// A value of the document at `field`, read as serde asks.
struct Reader<'a> {
    value: &'a toml::Value,
    field: String,
}

impl<'de> de::Deserializer<'de> for Reader<'_> {
    type Error = ReadError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        match self.value {
            toml::Value::String(s) => visitor.visit_str(s),
            toml::Value::Integer(i) => visitor.visit_i64(*i),
            toml::Value::Float(x) => visitor.visit_f64(*x),
            toml::Value::Boolean(b) => visitor.visit_bool(*b),
            toml::Value::Datetime(d) => visitor.visit_string(d.to_string()),
            toml::Value::Array(list) => {
                let mut elements = Elements {
                    list: list.iter().enumerate(),
                    field: &self.field,
                    ran_out: false,
                };
                let read = visitor.visit_seq(&mut elements);
                let left = elements.list.len();
                let length = |expected, message| ReadError {
                    field: Some(self.field.clone()),
                    message,
                    length: Some(Length {
                        given: list.len(),
                        expected,
                    }),
                };
                match read {
                    // Full before the list ended: elements left over.
                    Ok(_) if left > 0 => Err(length(Some(list.len() - left), String::new())),
                    // Asked for an element after the last: too few.
                    Err(e) if elements.ran_out => Err(length(None, e.message)),
                    read => read,
                }
            }
            toml::Value::Table(table) => visitor.visit_map(Entries {
                entries: table.iter().collect::<Vec<_>>().into_iter(),
                value: None,
                field: &self.field,
            }),
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ReadError> {
        visitor.visit_some(self)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, ReadError> {
        match self.value {
            toml::Value::String(s) => visitor.visit_enum(s.as_str().into_deserializer()),
            _ => Err(de::Error::custom("expected a name")),
        }
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        unit unit_struct seq tuple tuple_struct map struct identifier ignored_any
    }
}

/// A list's elements, each read at `field[i]`.
struct Elements<'a> {
    list: std::iter::Enumerate<std::slice::Iter<'a, toml::Value>>,
    field: &'a str,
    /// Whether serde asked for an element after the last.
    ran_out: bool,
}

impl<'de> de::SeqAccess<'de> for Elements<'_> {
    type Error = ReadError;

    fn next_element_seed<S: DeserializeSeed<'de>>(
        &mut self,
        seed: S,
    ) -> Result<Option<S::Value>, ReadError> {
        let Some((i, value)) = self.list.next() else {
            self.ran_out = true;
            return Ok(None);
        };
        let field = format!("{}[{i}]", self.field);
        seed.deserialize(Reader {
            value,
            field: field.clone(),
        })
        .map(Some)
        .map_err(|e| e.at(&field))
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.list.len())
    }
}

/// A table's entries, each value read at `field.key`.
struct Entries<'a> {
    entries: std::vec::IntoIter<(&'a String, &'a toml::Value)>,
    value: Option<(String, &'a toml::Value)>,
    field: &'a str,
}

impl<'de> de::MapAccess<'de> for Entries<'_> {
    type Error = ReadError;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, ReadError> {
        let Some((key, value)) = self.entries.next() else {
            return Ok(None);
        };
        let field = match self.field {
            "" => key.clone(),
            table => format!("{table}.{key}"),
        };
        let read = seed
            .deserialize(key.as_str().into_deserializer())
            .map_err(|e: ReadError| e.at(&field));
        self.value = Some((field, value));
        read.map(Some)
    }

    fn next_value_seed<S: DeserializeSeed<'de>>(&mut self, seed: S) -> Result<S::Value, ReadError> {
        let Some((field, value)) = self.value.take() else {
            return Err(de::Error::custom("a value without its key"));
        };
        seed.deserialize(Reader {
            value,
            field: field.clone(),
        })
        .map_err(|e| e.at(&field))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::EnvConfig;

    fn refusal(text: &str) -> Option<String> {
        let doc: toml::Table = toml::from_str(text).unwrap();
        check_lists::<EnvConfig>(&doc).err().map(|e| e.to_string())
    }

    #[test]
    fn a_list_longer_or_shorter_than_its_field_is_refused_naming_the_field() {
        assert_eq!(
            refusal("[task.place]\nfixture_friction = [0.3, 1.2, 9.0]\n").as_deref(),
            Some(
                "task.place.fixture_friction = [0.3, 1.2, 9.0]: has 3 elements: it must hold \
                 exactly 2"
            )
        );
        let m = refusal("[task.stack]\nbase_radius = [0.25, 0.4, \"junk\", {a = 1}]\n").unwrap();
        assert!(
            m.starts_with("task.stack.base_radius = [0.25, 0.4, \"junk\", { a = 1 }]: has 4 elements and mixes a number, a string and a table: it must hold exactly 2, of one type"),
            "{m}"
        );
        let m = refusal("[arm]\nhome_joints = [0.0, 0.0, 0.0, 0.0, 0.0]\n").unwrap();
        assert!(
            m.starts_with("arm.home_joints = [0.0, 0.0, 0.0, 0.0, 0.0]: has 5 elements: ")
                && m.contains("length 6"),
            "{m}"
        );
        let m = refusal(
            "[randomization.nudge]\ndistance = [0.01, 0.02]\nstep = [1]\nmin_tcp_distance = 0.2\n",
        )
        .unwrap();
        assert!(
            m.starts_with("randomization.nudge.step = [1]: has 1 element: "),
            "{m}"
        );
    }

    #[test]
    fn lists_of_the_right_length_and_other_errors_pass_to_the_typed_reader() {
        assert_eq!(
            refusal("[randomization]\nradius = [0.25, 0.4]\nfriction = [0.1, 0.2]\n"),
            None
        );
        // A wrong type or an unknown key is the typed reader's to refuse, citing the line.
        assert_eq!(refusal("[randomization]\nradius = [0.25, \"x\"]\n"), None);
        assert_eq!(refusal("[scene]\nnot_a_key = [1, 2, 3]\n"), None);
        // Every shipped preset passes too: loading one checks its lists
        // (`tests/range_messages.rs` loads them all).
    }
}

//! Reading a typed value from JSON in which a number may be `null` or absent: as NaN.
//!
//! JSON has no NaN: serde_json writes a NaN as `null`, and a writer may leave out a number
//! it does not have (the error bar of one realization, a cross-check that has no value).
//! [`from_value`] reads such JSON into the same types serde_json reads it into, with one
//! difference: an `f64` (or `f32`) field that is `null` or absent reads as NaN. Everything
//! else is read exactly as serde_json reads it: an `Option` that is `null` or absent is
//! `None`, a default applies where the type declares one, and `null` in a string or an
//! absent field of any other type is the same error as always.
//!
//! How: a deserializer over [`serde_json::Value`] that answers a request for a float on
//! `null` with NaN and hands every other leaf to serde_json. An absent field shows up as
//! the "missing field" error of the type's derived visitor; the deserializer notes the
//! object and the field, and the read starts again with that field present in the object
//! as "absent": NaN for a float, `None` for an option, the same "missing field" error for
//! any other type. Each retry marks one more field, so the reads end. Enums are read by
//! serde_json itself (no float inside an enum's variant is read leniently).

use std::cell::Cell;
use std::collections::{HashMap, HashSet};

use serde::de::value::BorrowedStrDeserializer;
use serde::de::{self, DeserializeOwned, DeserializeSeed, Deserializer, MapAccess, SeqAccess};
use serde::forward_to_deserialize_any;
use serde_json::{Error, Map, Value};

/// An object of the JSON tree, by address (the tree is not changed between reads).
type ObjectId = usize;

/// Reads `T` from `value`, every `f64` that is `null` or absent read as NaN.
pub fn from_value<T: DeserializeOwned>(value: &Value) -> Result<T, Error> {
    let mut absent: HashSet<(ObjectId, &'static str)> = HashSet::new();
    loop {
        let mut by_object: HashMap<ObjectId, Vec<&'static str>> = HashMap::new();
        for &(object, field) in &absent {
            by_object.entry(object).or_default().push(field);
        }
        for fields in by_object.values_mut() {
            fields.sort_unstable();
        }
        let read = Read {
            absent: by_object,
            missing: Cell::new(None),
        };
        match T::deserialize(Lenient { value, read: &read }) {
            Ok(t) => return Ok(t),
            Err(e) => match read.missing.take() {
                Some(slot) if absent.insert(slot) => continue,
                _ => return Err(e),
            },
        }
    }
}

/// What one read knows: the fields marked absent, and the first missing field it met.
struct Read {
    absent: HashMap<ObjectId, Vec<&'static str>>,
    missing: Cell<Option<(ObjectId, &'static str)>>,
}

fn object_id(map: &Map<String, Value>) -> ObjectId {
    std::ptr::from_ref(map) as ObjectId
}

/// The deserializer of one node of the tree.
struct Lenient<'de> {
    value: &'de Value,
    read: &'de Read,
}

impl<'de> Lenient<'de> {
    fn entries(&self, map: &'de Map<String, Value>) -> Entries<'de> {
        let absent = self
            .read
            .absent
            .get(&object_id(map))
            .map_or(&[][..], Vec::as_slice);
        Entries {
            present: map.iter(),
            absent: absent.iter(),
            next: None,
            read: self.read,
        }
    }
}

impl<'de> Deserializer<'de> for Lenient<'de> {
    type Error = Error;

    fn deserialize_any<V: de::Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.value {
            Value::Object(map) => visitor.visit_map(self.entries(map)),
            Value::Array(items) => visitor.visit_seq(Items {
                items: items.iter(),
                read: self.read,
            }),
            leaf => leaf.deserialize_any(visitor),
        }
    }

    fn deserialize_f64<V: de::Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.value {
            Value::Null => visitor.visit_f64(f64::NAN),
            leaf => leaf.deserialize_f64(visitor),
        }
    }

    fn deserialize_f32<V: de::Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.value {
            Value::Null => visitor.visit_f32(f32::NAN),
            leaf => leaf.deserialize_f32(visitor),
        }
    }

    fn deserialize_option<V: de::Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.value {
            Value::Null => visitor.visit_none(),
            _ => visitor.visit_some(self),
        }
    }

    fn deserialize_newtype_struct<V: de::Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Error> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_struct<V: de::Visitor<'de>>(
        self,
        name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        let Value::Object(map) = self.value else {
            return self.value.deserialize_struct(name, fields, visitor);
        };
        let result = visitor.visit_map(self.entries(map));
        if let Err(e) = &result {
            // The innermost object with the field reports it first.
            let message = e.to_string();
            let missing = fields
                .iter()
                .find(|f| !map.contains_key(**f) && message == format!("missing field `{f}`"));
            if let (None, Some(&field)) = (self.read.missing.get(), missing) {
                self.read.missing.set(Some((object_id(map), field)));
            }
        }
        result
    }

    fn deserialize_enum<V: de::Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        self.value.deserialize_enum(name, variants, visitor)
    }

    fn deserialize_ignored_any<V: de::Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_unit()
    }

    forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 char str string bytes byte_buf unit
        unit_struct seq tuple tuple_struct map identifier
    }
}

/// The value of a field marked absent: NaN for a float, `None` for an option, and the
/// "missing field" error for anything else.
struct Absent(&'static str);

impl<'de> Deserializer<'de> for Absent {
    type Error = Error;

    fn deserialize_any<V: de::Visitor<'de>>(self, _visitor: V) -> Result<V::Value, Error> {
        Err(de::Error::missing_field(self.0))
    }

    fn deserialize_f64<V: de::Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_f64(f64::NAN)
    }

    fn deserialize_f32<V: de::Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_f32(f32::NAN)
    }

    fn deserialize_option<V: de::Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_none()
    }

    forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 char str string bytes byte_buf unit
        unit_struct newtype_struct seq tuple tuple_struct map struct enum identifier
        ignored_any
    }
}

/// The fields of an object: those present, then those marked absent.
struct Entries<'de> {
    present: serde_json::map::Iter<'de>,
    absent: std::slice::Iter<'de, &'static str>,
    next: Option<Result<&'de Value, &'static str>>,
    read: &'de Read,
}

impl<'de> MapAccess<'de> for Entries<'de> {
    type Error = Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Error> {
        let key: &'de str = if let Some((key, value)) = self.present.next() {
            self.next = Some(Ok(value));
            key
        } else if let Some(&field) = self.absent.next() {
            self.next = Some(Err(field));
            field
        } else {
            return Ok(None);
        };
        seed.deserialize(BorrowedStrDeserializer::new(key))
            .map(Some)
    }

    fn next_value_seed<S: DeserializeSeed<'de>>(&mut self, seed: S) -> Result<S::Value, Error> {
        match self.next.take() {
            Some(Ok(value)) => seed.deserialize(Lenient {
                value,
                read: self.read,
            }),
            Some(Err(field)) => seed.deserialize(Absent(field)),
            None => Err(de::Error::custom("a value asked for before its key")),
        }
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.present.len() + self.absent.len())
    }
}

/// The items of an array.
struct Items<'de> {
    items: std::slice::Iter<'de, Value>,
    read: &'de Read,
}

impl<'de> SeqAccess<'de> for Items<'de> {
    type Error = Error;

    fn next_element_seed<S: DeserializeSeed<'de>>(
        &mut self,
        seed: S,
    ) -> Result<Option<S::Value>, Error> {
        self.items
            .next()
            .map(|value| {
                seed.deserialize(Lenient {
                    value,
                    read: self.read,
                })
            })
            .transpose()
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.items.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;
    use serde_json::json;

    #[derive(Debug, Deserialize, PartialEq)]
    struct Estimate {
        value: f64,
        std_error: f64,
    }

    #[derive(Debug, Deserialize)]
    struct Record {
        name: String,
        headline: Estimate,
        rows: Vec<Estimate>,
        other: Option<Estimate>,
        grid: Option<usize>,
        #[serde(default = "yes")]
        decided: bool,
    }

    fn yes() -> bool {
        true
    }

    fn is_nan(x: f64) -> bool {
        x.is_nan()
    }

    #[test]
    fn null_and_absent_floats_read_as_nan_and_nothing_else_changes() {
        let v = json!({
            "name": "a",
            "headline": {"value": 2.5, "std_error": null},
            "rows": [{"value": 1, "std_error": 0.5}, {"value": null}],
            "other": null,
        });
        let r: Record = from_value(&v).unwrap();
        assert_eq!(r.name, "a");
        assert_eq!(r.headline.value, 2.5);
        assert!(is_nan(r.headline.std_error));
        assert_eq!(
            r.rows[0],
            Estimate {
                value: 1.0,
                std_error: 0.5
            }
        );
        assert!(is_nan(r.rows[1].value) && is_nan(r.rows[1].std_error));
        assert_eq!(r.other, None);
        assert_eq!(r.grid, None);
        assert!(r.decided, "the type's default applies");
        // Equal to serde_json where serde_json reads it.
        let full = json!({
            "name": "b", "headline": {"value": 1, "std_error": 2},
            "rows": [], "other": {"value": 3, "std_error": 4}, "grid": 64, "decided": false,
        });
        let (a, b): (Record, Record) = (from_value(&full).unwrap(), {
            serde_json::from_value(full.clone()).unwrap()
        });
        assert_eq!((a.other, a.grid, a.decided), (b.other, b.grid, b.decided));
    }

    #[test]
    fn other_types_stay_strict() {
        let absent_name = json!({"headline": {"value": 1, "std_error": 1}, "rows": []});
        let e = from_value::<Record>(&absent_name).unwrap_err().to_string();
        assert_eq!(e, "missing field `name`");
        let null_name = json!({"name": null, "headline": {"value": 1}, "rows": []});
        let e = from_value::<Record>(&null_name).unwrap_err().to_string();
        assert!(e.contains("invalid type: null"), "{e}");
        let absent_headline = json!({"name": "a", "rows": []});
        let e = from_value::<Record>(&absent_headline)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "missing field `headline`");
        let text = json!({"name": "a", "headline": {"value": "x", "std_error": 1}, "rows": []});
        assert!(from_value::<Record>(&text).is_err());
    }
}

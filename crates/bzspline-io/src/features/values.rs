//! A layer's field values, row after row, held compactly: one 16-byte slot
//! a value and every string in one buffer, where a JSON value takes 72
//! bytes and a string an allocation of its own.

use serde_json::Value;

/// One value: the number itself, or where its text or JSON value is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Slot {
    Null,
    Bool(bool),
    /// A whole number within `i64`.
    Int(i64),
    /// Any other number.
    Float(f64),
    /// A string: `len` bytes of the text buffer from `start`.
    Text {
        start: u64,
        len: u32,
    },
    /// Any other value (an array, an object, a whole number past `i64`, a
    /// string of 4 GiB or more): the index of the JSON value.
    Json(usize),
}

/// Rows of values, each as many as the table has fields.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Values {
    slots: Vec<Slot>,
    text: String,
    json: Vec<Value>,
}

impl Values {
    /// Adds `v` after the last value.
    pub(super) fn push(&mut self, v: &Value) {
        let slot = match v {
            Value::Null => Slot::Null,
            Value::Bool(b) => Slot::Bool(*b),
            Value::Number(n) => match (n.as_i64(), n.as_f64()) {
                (Some(i), _) => Slot::Int(i),
                (None, Some(f)) if n.is_f64() => Slot::Float(f),
                _ => self.json(v),
            },
            Value::String(t) => match u32::try_from(t.len()) {
                Ok(len) => {
                    let start = self.text.len() as u64;
                    self.text.push_str(t);
                    Slot::Text { start, len }
                }
                Err(_) => self.json(v),
            },
            _ => self.json(v),
        };
        self.slots.push(slot);
    }

    fn json(&mut self, v: &Value) -> Slot {
        self.json.push(v.clone());
        Slot::Json(self.json.len() - 1)
    }

    /// Value `i` as it was given.
    pub(super) fn get(&self, i: usize) -> Value {
        match self.slots[i] {
            Slot::Null => Value::Null,
            Slot::Bool(b) => Value::Bool(b),
            Slot::Int(i) => Value::from(i),
            Slot::Float(f) => Value::from(f),
            Slot::Text { start, len } => {
                let start = start as usize;
                Value::String(self.text[start..start + len as usize].to_owned())
            }
            Slot::Json(k) => self.json[k].clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn values_come_back_as_given_with_their_text() {
        let values = [
            json!(null),
            json!(true),
            json!(false),
            json!(0),
            json!(-7),
            json!(i64::MIN),
            json!(i64::MAX),
            json!(i64::MAX as u64 + 1),
            json!(u64::MAX),
            json!(5.0),
            json!(-0.0),
            json!(0.1),
            json!(1e300),
            json!(-2.5e-310),
            json!(""),
            json!("Zürich \"quoted\""),
            json!("€"),
            json!([1, "a", null]),
            json!({"b": 1, "a": [2.5]}),
        ];
        let mut store = Values::default();
        // Twice over, so that text follows text and other values.
        for v in values.iter().chain(&values) {
            store.push(v);
        }
        assert_eq!(store.slots.len(), 2 * values.len());
        for (i, v) in values.iter().chain(&values).enumerate() {
            let back = store.get(i);
            assert_eq!(&back, v);
            assert_eq!(back.to_string(), v.to_string(), "{v}");
        }
        // A whole number past i64 is not made a float.
        assert!(matches!(store.slots[8], Slot::Json(_)));
        assert_eq!(store.slots[4], Slot::Int(-7));
        assert_eq!(store.slots[9], Slot::Float(5.0));
        // Both copies of the strings are in the one buffer.
        assert_eq!(store.text, "Zürich \"quoted\"€".repeat(2));
        assert_eq!(std::mem::size_of::<Slot>(), 16);
    }
}

//! A peer's decoded fields, compared with a vector's `fields`.

use serde_json::Value;

/// One decoded value, in the forms the vectors record.
#[derive(Clone, Debug, PartialEq)]
pub enum V {
    /// An integer (enums and bit words as their raw value).
    I(i128),
    /// A float32, compared exactly: the vectors hold its value as a double, which is rounded
    /// back to float32 first (serde_json's default parser may be one double ulp off).
    F(f32),
    /// Text up to the first NUL.
    S(String),
    /// A list of integers.
    List(Vec<i128>),
    /// A list of texts.
    Strings(Vec<String>),
}

impl V {
    fn matches(&self, recorded: &Value) -> bool {
        match self {
            V::I(x) => {
                recorded.as_i64().map(i128::from) == Some(*x)
                    || recorded.as_u64().map(i128::from) == Some(*x)
            }
            V::F(x) => recorded.as_f64().map(|r| r as f32) == Some(*x),
            V::S(s) => recorded.as_str() == Some(s),
            V::List(xs) => recorded.as_array().is_some_and(|a| {
                a.len() == xs.len() && a.iter().zip(xs).all(|(r, x)| V::I(*x).matches(r))
            }),
            V::Strings(xs) => recorded.as_array().is_some_and(|a| {
                a.len() == xs.len() && a.iter().zip(xs).all(|(r, x)| r.as_str() == Some(x))
            }),
        }
    }

    fn is_zero(&self) -> bool {
        match self {
            V::I(x) => *x == 0,
            V::F(x) => *x == 0.0,
            V::S(s) => s.is_empty(),
            V::List(xs) => xs.iter().all(|x| *x == 0),
            V::Strings(xs) => xs.is_empty(),
        }
    }
}

/// Every recorded field equals the peer's; a field the peer has and the vector does not list
/// (an extension field a MAVLink 1 frame cannot carry) must be zero.
///
/// # Panics
///
/// On the first difference, or on a recorded field the peer does not decode.
pub fn assert_fields(frame: &str, got: &[(&str, V)], recorded: &Value) {
    let recorded = recorded.as_object().expect("fields is an object");
    for (key, value) in got {
        match recorded.get(*key) {
            Some(r) => assert!(
                value.matches(r),
                "{frame}.{key}: peer {value:?}, vector {r}"
            ),
            None => assert!(
                value.is_zero(),
                "{frame}.{key}: peer {value:?}, not in the vector"
            ),
        }
    }
    for key in recorded.keys() {
        assert!(
            got.iter().any(|(k, _)| k == key),
            "{frame}.{key}: recorded but not decoded by the peer"
        );
    }
}

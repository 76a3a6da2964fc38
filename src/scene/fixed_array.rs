//! Fixed-size arrays of scenes (`size = [2.0, 1.0]`) read strictly: serde's `[T; N]` reads the
//! first N values of a longer array and drops the rest, so `size = [2.0, 1.0, 99.0]` or
//! `divisions = [24, 12, -5]` were accepted; here any length but N is an error that gives the
//! length found and the one expected (the TOML reader adds the key).

use serde::de::{Deserialize, Deserializer, Error};

/// Exactly N values.
pub fn exact<'de, D, T, const N: usize>(d: D) -> Result<[T; N], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    let v: Vec<T> = Vec::deserialize(d)?;
    let len = v.len();
    v.try_into()
        .map_err(|_| D::Error::custom(format!("{len} values, expected exactly {N}")))
}

/// An optional key of exactly N values.
pub fn exact_option<'de, D, T, const N: usize>(d: D) -> Result<Option<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    exact(d).map(Some)
}

#[cfg(test)]
mod tests {
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    struct Pair {
        #[serde(deserialize_with = "super::exact")]
        size: [f64; 2],
        #[serde(default, deserialize_with = "super::exact_option")]
        divisions: Option<[usize; 2]>,
    }

    #[test]
    fn two_values_read_and_any_other_length_is_an_error_naming_the_key() {
        let p: Pair = toml::from_str("size = [2.0, 1.0]").unwrap();
        assert_eq!(p.size, [2.0, 1.0]);
        assert_eq!(p.divisions, None);
        let p: Pair = toml::from_str("size = [2.0, 1.0]\ndivisions = [3, 4]").unwrap();
        assert_eq!(p.divisions, Some([3, 4]));
        for (text, key) in [
            ("size = [2.0, 1.0, 99.0]", "size"),
            ("size = [2.0]", "size"),
            ("size = [2.0, 1.0]\ndivisions = [24, 12, 5]", "divisions"),
        ] {
            let e = toml::from_str::<Pair>(text).unwrap_err().to_string();
            assert!(
                e.contains("expected exactly 2") && e.contains(key),
                "{text}: {e}"
            );
        }
        // a bad element is reported first, at its place
        let e = toml::from_str::<Pair>("size = [2.0, 1.0]\ndivisions = [24, 12, -5]")
            .unwrap_err()
            .to_string();
        assert!(e.contains("divisions") && e.contains("-5"), "{e}");
    }
}

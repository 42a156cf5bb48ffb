//! Fixed-length arrays read exactly: serde's arrays take the first `N`
//! elements of a longer TOML array and drop the rest, so
//! `gravity = [0, 0, -9.81, 7]` would pass as `[0, 0, -9.81]`. These
//! readers refuse any other length, with serde's "invalid length" error
//! (which the diagnostics turn into "expected an array of 3 numbers …,
//! found 4 elements" at the key).

use serde::de::{Deserialize, Deserializer, Error};

fn to_array<T, E: Error, const N: usize>(v: Vec<T>) -> Result<[T; N], E> {
    let n = v.len();
    v.try_into()
        .map_err(|_| E::invalid_length(n, &format!("an array of length {N}").as_str()))
}

/// `Option<[T; N]>` of exactly `N` elements (use with `#[serde(default)]`).
pub fn array<'de, D, T, const N: usize>(d: D) -> Result<Option<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Option::<Vec<T>>::deserialize(d)?.map(to_array).transpose()
}

/// `Option<Vec<[T; N]>>`, every row of exactly `N` elements.
pub fn rows<'de, D, T, const N: usize>(d: D) -> Result<Option<Vec<[T; N]>>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Option::<Vec<Vec<T>>>::deserialize(d)?
        .map(|v| v.into_iter().map(to_array).collect())
        .transpose()
}

/// `Option<[[T; N]; N]>`: an `N × N` matrix, rows and columns exact.
pub fn matrix<'de, D, T, const N: usize>(d: D) -> Result<Option<[[T; N]; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    match rows::<D, T, N>(d)? {
        None => Ok(None),
        Some(r) => to_array(r).map(Some),
    }
}

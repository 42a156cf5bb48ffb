//! Python sees bodies sorted by global id and spheres by global sphere id,
//! whatever order the engine keeps them in (it re-sorts them spatially at
//! neighbour builds). The order is cached and checked in O(n) on each use.

/// The storage indices that list `ids` in ascending order, reusing `cache`
/// when it still does.
pub fn ascending(ids: &[u64], cache: &mut Vec<usize>) {
    let valid = cache.len() == ids.len()
        && cache.iter().all(|&i| i < ids.len())
        && cache.windows(2).all(|w| ids[w[0]] < ids[w[1]]);
    if !valid {
        cache.clear();
        cache.extend(0..ids.len());
        cache.sort_unstable_by_key(|&i| ids[i]);
    }
}

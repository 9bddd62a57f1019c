//! Clusters of the contact stage: the grains linked by close pairs (connected components).

/// Groups of grains linked by pairs (connected components), each sorted, the groups ordered by
/// their first grain.
pub fn clusters(pairs: &[(usize, usize)]) -> Vec<Vec<usize>> {
    use std::collections::HashMap;
    let mut parent: HashMap<usize, usize> = HashMap::new();
    fn find(parent: &mut HashMap<usize, usize>, i: usize) -> usize {
        let mut r = i;
        while let Some(&p) = parent.get(&r) {
            if p == r {
                break;
            }
            r = p;
        }
        // Path compression.
        let mut k = i;
        while k != r {
            let next = parent[&k];
            parent.insert(k, r);
            k = next;
        }
        r
    }
    for &(i, j) in pairs {
        parent.entry(i).or_insert(i);
        parent.entry(j).or_insert(j);
        let (a, b) = (find(&mut parent, i), find(&mut parent, j));
        if a != b {
            parent.insert(a.max(b), a.min(b));
        }
    }
    let keys: Vec<usize> = parent.keys().copied().collect();
    let mut groups: HashMap<usize, Vec<usize>> = HashMap::new();
    for k in keys {
        let r = find(&mut parent, k);
        groups.entry(r).or_default().push(k);
    }
    let mut out: Vec<Vec<usize>> = groups
        .into_values()
        .map(|mut g| {
            g.sort_unstable();
            g
        })
        .collect();
    out.sort_unstable_by_key(|g| g[0]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clusters_are_connected_components() {
        let c = clusters(&[(1, 5), (5, 9), (2, 3), (9, 1)]);
        assert_eq!(c, vec![vec![1, 5, 9], vec![2, 3]]);
    }
}

//! The kinematic tree of a URDF: parent joint and child joints of every link, one root, no
//! cycles. Every walk is iterative, so a chain of any length (within the size limits) loads.

use super::err;
use super::xml::Raw;
use crate::error::Result;

pub(super) struct Tree {
    /// The joint whose child each link is (`None` for the root).
    pub parent_joint: Vec<Option<usize>>,
    /// Child joints of link `l`: `children[start[l]..start[l + 1]]` (file order).
    start: Vec<usize>,
    children: Vec<usize>,
    pub root: usize,
    /// Links in depth-first order from the root (parents before children).
    pub order: Vec<usize>,
    /// Number of joints between the root and each link.
    pub depth: Vec<usize>,
}

impl Tree {
    /// Builds the tree in O(links + joints): a link with two parents, several roots or links that
    /// cannot be reached from the root (a cycle) are errors naming them.
    pub fn new(raw: &Raw) -> Result<Tree> {
        let n = raw.links.len();
        let mut parent_joint: Vec<Option<usize>> = vec![None; n];
        let mut count = vec![0usize; n + 1];
        for (j, joint) in raw.joints.iter().enumerate() {
            if let Some(other) = parent_joint[joint.child].replace(j) {
                return err(format!(
                    "link '{}' is the child of several joints ('{}' and '{}')",
                    raw.links[joint.child].name, raw.joints[other].name, joint.name
                ));
            }
            count[joint.parent + 1] += 1;
        }
        // Child lists by a counting sort on the parent link.
        for l in 0..n {
            count[l + 1] += count[l];
        }
        let start = count.clone();
        let mut fill = count;
        let mut children = vec![0usize; raw.joints.len()];
        for (j, joint) in raw.joints.iter().enumerate() {
            children[fill[joint.parent]] = j;
            fill[joint.parent] += 1;
        }
        let root = the_root(raw, &parent_joint)?;
        let mut tree = Tree {
            parent_joint,
            start,
            children,
            root,
            order: Vec::with_capacity(n),
            depth: vec![0; n],
        };
        let mut stack = vec![tree.root];
        while let Some(l) = stack.pop() {
            tree.order.push(l);
            for k in (tree.start[l]..tree.start[l + 1]).rev() {
                let c = raw.joints[tree.children[k]].child;
                tree.depth[c] = tree.depth[l] + 1;
                stack.push(c);
            }
        }
        if tree.order.len() != n {
            return err(unreachable(raw, &tree));
        }
        Ok(tree)
    }

    /// The joints whose parent is link `l`.
    pub fn child_joints(&self, l: usize) -> &[usize] {
        &self.children[self.start[l]..self.start[l + 1]]
    }

    /// Joints from the root to link `l`, root first.
    pub fn path_to(&self, raw: &Raw, l: usize) -> Vec<usize> {
        let mut path = Vec::with_capacity(self.depth[l]);
        let mut link = l;
        while let Some(j) = self.parent_joint[link] {
            path.push(j);
            link = raw.joints[j].parent;
        }
        path.reverse();
        path
    }
}

/// The one link that is no joint's child; errors for none (a cycle) or several.
fn the_root(raw: &Raw, parent_joint: &[Option<usize>]) -> Result<usize> {
    if raw.links.is_empty() {
        return err("the file has no <link> element".into());
    }
    let roots: Vec<usize> = (0..raw.links.len())
        .filter(|&l| parent_joint[l].is_none())
        .collect();
    match roots.len() {
        1 => Ok(roots[0]),
        0 => {
            err("no root link: every link is the child of a joint (the joints form a cycle)".into())
        }
        k => {
            let mut names: Vec<&str> = roots.iter().map(|&l| raw.links[l].name.as_str()).collect();
            names.sort_unstable();
            let shown = k.min(5);
            let more = if k > shown { ", …" } else { "" };
            err(format!(
                "expected one root link, found {k} ({}{more})",
                names[..shown].join(", ")
            ))
        }
    }
}

/// The error for links that the walk from the root did not reach (they form a cycle).
fn unreachable(raw: &Raw, tree: &Tree) -> String {
    let mut seen = vec![false; raw.links.len()];
    for &l in &tree.order {
        seen[l] = true;
    }
    let lost = (0..raw.links.len())
        .find(|&l| !seen[l])
        .map_or("", |l| raw.links[l].name.as_str());
    format!(
        "link '{lost}' cannot be reached from the root link '{}': the joints form a cycle",
        raw.links[tree.root].name
    )
}

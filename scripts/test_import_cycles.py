#!/usr/bin/env python3
"""Tests of scripts/import_cycles.py on small crates written to a temporary folder.

Run: python3 scripts/test_import_cycles.py
"""

import contextlib
import io
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import import_cycles  # noqa: E402


def crate(files):
    """A temporary src folder holding `files` (relative path -> text)."""
    d = tempfile.mkdtemp()
    for rel, text in files.items():
        path = os.path.join(d, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    return d


def edges(d):
    _, e = import_cycles.build_graph(d)
    return {(os.path.relpath(a, d), os.path.relpath(b, d)) for a, b in e}


def circles(d):
    with contextlib.redirect_stdout(io.StringIO()):
        return import_cycles.check(d)


def exit_status(d):
    with contextlib.redirect_stdout(io.StringIO()):
        return import_cycles.main([d])


class ImportCycles(unittest.TestCase):
    def test_a_circle_through_use_and_super_is_found(self):
        d = crate({
            "lib.rs": "mod a;\nmod b;\nmod c;\n",
            "a.rs": "use crate::b::B;\npub struct A;\n",
            "b.rs": "pub struct B;\nfn f() { super::c::g(); }\n",
            "c.rs": "pub fn g() { let _ = crate::a::A; }\n",
        })
        self.assertEqual(edges(d), {("a.rs", "b.rs"), ("b.rs", "c.rs"), ("c.rs", "a.rs")})
        self.assertEqual(circles(d), 1)
        self.assertEqual(exit_status(d), 1)

    def test_reexports_of_the_root_lead_to_the_defining_file(self):
        # `crate::Model` is `model::Model`: model -> error and error -> lib would be a false
        # circle through lib.rs (which depends on model by its re-export).
        d = crate({
            "lib.rs": "mod error;\nmod model;\npub use error::Error;\npub use model::Model;\n",
            "model.rs": "use crate::Error;\npub struct Model;\n",
            "error.rs": "pub enum Error { A }\n",
        })
        self.assertEqual(
            edges(d), {("lib.rs", "error.rs"), ("lib.rs", "model.rs"), ("model.rs", "error.rs")}
        )
        self.assertEqual(circles(d), 0)
        self.assertEqual(exit_status(d), 0)

    def test_comments_strings_and_inline_test_modules(self):
        d = crate({
            "lib.rs": "mod a;\nmod b;\n",
            # Paths in comments and strings are not dependencies; `super` in an inline module
            # is the file itself.
            "a.rs": "//! See [`crate::b::B`].\n/* crate::b::B */\npub fn a() -> &'static str "
                    "{ \"crate::b::B\" }\n#[cfg(test)]\nmod tests {\n    use super::a;\n}\n",
            "b.rs": "use crate::a::a;\npub struct B;\n",
        })
        self.assertEqual(edges(d), {("b.rs", "a.rs")})
        self.assertEqual(circles(d), 0)

    def test_folders_path_attributes_and_globs(self):
        d = crate({
            "lib.rs": "mod fast;\nmod update;\n",
            "update/mod.rs": "mod step;\npub(crate) use step::*;\n",
            "update/step.rs": "pub(crate) fn step() {}\n",
            "fast/mod.rs": "#[path = \"impl_2d.rs\"]\nmod plane;\nuse crate::update::step;\n",
            "fast/impl_2d.rs": "use super::super::update::{self, step as s};\n",
        })
        self.assertEqual(
            edges(d),
            {
                ("update/mod.rs", "update/step.rs"),
                ("fast/mod.rs", "update/step.rs"),
                ("fast/impl_2d.rs", "update/step.rs"),
                ("fast/impl_2d.rs", "update/mod.rs"),
            },
        )
        self.assertEqual(circles(d), 0)

    def test_a_parent_and_its_child_using_each_other_is_a_circle(self):
        d = crate({
            "lib.rs": "mod learner;\n",
            "learner.rs": "#[path = \"learner_step.rs\"]\nmod step;\npub use step::Step;\n"
                          "pub struct Learner;\n",
            "learner_step.rs": "use super::Learner;\npub struct Step;\n",
        })
        self.assertEqual(circles(d), 1)


if __name__ == "__main__":
    unittest.main()

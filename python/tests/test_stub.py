"""The stub sctl/__init__.pyi against the package: the keywords of `segment`
and their defaults (the stub's keyword list is generated from the key table
of the Rust crates; this checks it against what the built package takes)."""

import ast
import inspect
from pathlib import Path

import sctl

STUB = Path(__file__).resolve().parents[1] / "sctl" / "__init__.pyi"


def stub_segment():
    """The stub's `segment` definition, parsed."""
    tree = ast.parse(STUB.read_text())
    return next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "segment")


def stub_keywords():
    """The stub's keyword-only parameters of `segment` with their defaults."""
    args = stub_segment().args
    return {a.arg: ast.literal_eval(d) for a, d in zip(args.kwonlyargs, args.kw_defaults)}


def test_stub_positional_parameters_are_the_packages():
    package = inspect.signature(sctl.segment).parameters.values()
    positional = [p.name for p in package if p.kind == p.POSITIONAL_OR_KEYWORD]
    assert [a.arg for a in stub_segment().args.args] == positional


def test_stub_keywords_and_defaults_are_the_packages():
    stub = stub_keywords()
    package = inspect.signature(sctl.segment).parameters.values()
    explicit = {p.name: p.default for p in package if p.kind == p.KEYWORD_ONLY}
    params = sctl.default_params()
    assert set(stub) == set(explicit) | set(params), (
        f"only in the stub: {sorted(set(stub) - set(explicit) - set(params))}; "
        f"only in the package: {sorted((set(explicit) | set(params)) - set(stub))}"
    )
    for name, default in explicit.items():
        assert stub[name] == default, name
    for name, default in params.items():
        assert stub[name] == default and type(stub[name]) is type(default), (name, stub[name], default)


def test_every_stub_keyword_is_accepted(synthetic):
    scene = sctl.load_hopef(synthetic[0])
    keywords = {k: v for k, v in stub_keywords().items() if k not in ("principal_point", "focal_prior")}
    seg = sctl.segment(scene["x1"], scene["x2"], scene["image_size"], **{**keywords, "num_samples": 50})
    assert seg.params == {**sctl.default_params(), "num_samples": 50}

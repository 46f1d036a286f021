"""inspect.signature() of every public function and method equals the stub __init__.pyi."""

import ast
import inspect
import pathlib
import re

import numpy as np
import pytest

import sfit
from sfit import _signatures

STUB = pathlib.Path(sfit.__file__).with_name("__init__.pyi")
CLASSES = ["Surface", "Fit", "IncrementalFit", "FrozenRefit", "Curve", "CurveFit"]


def stub_signature(node):
    """(name, kind, default) of each parameter of a stub def (defaults as values)."""
    a = node.args
    out = []
    positional = a.posonlyargs + a.args
    first = len(positional) - len(a.defaults)
    for k, p in enumerate(positional):
        kind = "POSITIONAL_ONLY" if k < len(a.posonlyargs) else "POSITIONAL_OR_KEYWORD"
        d = ast.literal_eval(a.defaults[k - first]) if k >= first else "<empty>"
        out.append((p.arg, kind, d))
    if a.vararg:
        out.append((a.vararg.arg, "VAR_POSITIONAL", "<empty>"))
    for p, d in zip(a.kwonlyargs, a.kw_defaults):
        out.append((p.arg, "KEYWORD_ONLY", "<empty>" if d is None else ast.literal_eval(d)))
    if a.kwarg:
        out.append((a.kwarg.arg, "VAR_KEYWORD", "<empty>"))
    return out


def runtime_signature(obj):
    return [(p.name, p.kind.name, "<empty>" if p.default is p.empty else p.default)
            for p in inspect.signature(obj).parameters.values()]


def stub():
    tree = ast.parse(STUB.read_text())
    functions, classes = {}, {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            functions[node.name] = node
        elif isinstance(node, ast.ClassDef):
            methods = {n.name: n for n in node.body if isinstance(n, ast.FunctionDef)}
            attrs = {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
            classes[node.name] = (methods, attrs)
    return functions, classes


def public_callables(cls):
    for name, value in vars(cls).items():
        if name.startswith("_") and name not in ("__call__", "__init__"):
            continue
        if name == "__init__" and not inspect.isfunction(value):
            continue  # pybind11's "no constructor defined": the class is not made by calling it
        if isinstance(value, property) or type(value).__name__ == "property":
            continue
        if isinstance(value, staticmethod) or callable(value):
            yield name, getattr(cls, name)


def test_every_public_function_has_a_signature_equal_to_the_stub():
    functions, _ = stub()
    for name in sfit.__all__:
        obj = getattr(sfit, name)
        if inspect.isfunction(obj) or inspect.isbuiltin(obj):
            assert name in functions, f"{name} is missing from __init__.pyi"
            assert runtime_signature(obj) == stub_signature(functions[name]), name


@pytest.mark.parametrize("cls", CLASSES)
def test_every_public_method_has_a_signature_equal_to_the_stub(cls):
    _, classes = stub()
    methods, attrs = classes[cls]
    runtime = dict(public_callables(getattr(sfit, cls)))
    assert set(runtime) == set(methods) - {"__init__"} | ({"__init__"} & set(runtime)), cls
    for name, obj in runtime.items():
        assert runtime_signature(obj) == stub_signature(methods[name]), f"{cls}.{name}"
    properties = {n for n, v in vars(getattr(sfit, cls)).items()
                  if type(v).__name__ == "property" and not n.startswith("_")}
    assert properties == attrs, cls


def test_the_fit_keywords_are_those_the_compiled_fit_accepts():
    native = sfit.fit.__globals__["_native"]
    with pytest.raises(sfit.Error) as e:
        native(np.zeros((3, 3, 3)), None, no_such_option=1)
    known = re.search(r"known: ([^)]*)\)", str(e.value)).group(1).split(", ")
    assert known == [name for name, _ in _signatures.fit_keywords()]
    params = inspect.signature(sfit.fit).parameters
    assert list(params)[:2] == ["rows", "tol"]
    assert [p for p in params if params[p].kind is inspect.Parameter.KEYWORD_ONLY] == [
        k for k in known if k != "tol"]
    init = inspect.signature(sfit.IncrementalFit.__init__).parameters
    assert [p for p in init if init[p].kind is inspect.Parameter.KEYWORD_ONLY] == known


def test_a_call_the_signature_refuses_is_a_type_error():
    rows = np.zeros((3, 3, 3))
    with pytest.raises(TypeError):
        sfit.fit(rows, 0.1, 3)  # degree is keyword-only
    with pytest.raises(TypeError):
        sfit.fit(rows, no_such_option=1)
    s = sfit.fit(np.stack(np.meshgrid(np.arange(5.0), np.arange(4.0)) + [np.zeros((4, 5))], -1)).surface
    with pytest.raises(TypeError):
        s(0.1)
    assert inspect.signature(s.derivative).parameters["du"].default == 1


def test_docstrings_are_kept():
    assert "tolerance" in sfit.fit.__doc__
    assert "grid" in sfit.Surface.__call__.__doc__
    assert sfit.fit.__module__ == "sfit"

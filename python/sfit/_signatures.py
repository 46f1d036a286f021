"""True signatures for the compiled functions of sfit._sfit.

pybind11 functions are builtins: inspect.signature() cannot read them. pybind11 writes each
one's signature as the first line of its docstring ("name(a: T, b: T = 1) -> R"); install()
parses that line and puts in place of every public function and method a plain Python
function with exactly those parameters and defaults, which calls the compiled one (one extra
Python call, no argument re-parsing). fit() and IncrementalFit() take their options as
**kwargs in C++; their keyword-only parameters come from fit_keywords(), so they are made the
same way from whatever table lists the options.

The stub python/sfit/__init__.pyi is tested against these signatures
(python/tests/test_signatures.py), so the two cannot drift apart.
"""

import ast
import collections
import inspect

# The keywords of sfit.fit() and sfit.IncrementalFit() besides the rows (and fit()'s
# positional tol), in the order of the binding's option table (python/src/options.cpp). A
# value None means "the library's default"; test_signatures.py checks this list against the
# names the compiled fit() accepts.
# fit()'s keywords that are not options of the library's table: the count hints of
# search="known" and the progress callback.
EXTRA_FIT_KEYWORDS = ("row_count_hints", "column_count_hints", "progress")


def fit_keywords():
    """(name, default) of every fit option, in the order of the library's option table
    (sfit.fit_options(), group "fit"), then the extra keywords (default None)."""
    from . import _sfit

    table = [(o["name"], o["default"]) for o in _sfit.fit_options() if o["group"] == "fit"]
    return table + [(name, None) for name in EXTRA_FIT_KEYWORDS]


_P = inspect.Parameter


def native_signature(native):
    """The inspect.Signature pybind11 wrote as the first line of `native`'s docstring."""
    doc = (native.__doc__ or "").lstrip()
    first = doc.splitlines()[0] if doc else ""
    name = getattr(native, "__name__", "?")
    if not first.startswith(name + "(") or "Overloaded function" in doc[:200]:
        raise TypeError(f"{name}: no pybind11 signature line in its docstring")
    inner = first[len(name) + 1: first.rindex(")")]
    args = ast.parse(f"def f({inner}): pass").body[0].args
    params = []

    def default(node):
        return ast.literal_eval(node)

    positional = args.posonlyargs + args.args
    first_default = len(positional) - len(args.defaults)
    for k, a in enumerate(positional):
        kind = _P.POSITIONAL_ONLY if k < len(args.posonlyargs) else _P.POSITIONAL_OR_KEYWORD
        d = default(args.defaults[k - first_default]) if k >= first_default else _P.empty
        params.append(_P(a.arg, kind, default=d))
    if args.vararg:
        params.append(_P(args.vararg.arg, _P.VAR_POSITIONAL))
    for a, d in zip(args.kwonlyargs, args.kw_defaults):
        params.append(_P(a.arg, _P.KEYWORD_ONLY, default=_P.empty if d is None else default(d)))
    if args.kwarg:
        params.append(_P(args.kwarg.arg, _P.VAR_KEYWORD))
    return inspect.Signature(params)


def native_doc(native):
    """The docstring without pybind11's signature line."""
    lines = (native.__doc__ or "").lstrip().splitlines()[1:]
    return "\n".join(lines).strip() or None


def make_function(native, name, qualname, signature, doc):
    """A Python function `name` with `signature` that passes its arguments to `native`."""
    namespace = {"_native": native}
    parts, call, optional = [], [], []
    star = False
    for k, p in enumerate(signature.parameters.values()):
        text = p.name
        if p.default is not _P.empty:
            namespace[f"_d{k}"] = p.default
            text += f"=_d{k}"
        if p.kind is _P.VAR_POSITIONAL:
            text, star = "*" + p.name, True
            call.append("*" + p.name)
        elif p.kind is _P.VAR_KEYWORD:
            text = "**" + p.name
            call.append("**" + p.name)
        elif p.kind is _P.KEYWORD_ONLY:
            if not star:
                parts.append("*")
                star = True
            if p.default is _P.empty:
                call.append(f"{p.name}={p.name}")
            else:  # left at its default (this very object): not passed, the native's rules apply
                optional.append((p.name, f"_d{k}"))
        else:
            call.append(p.name)
        parts.append(text)
        if p.kind is _P.POSITIONAL_ONLY and (
                k + 1 == len(signature.parameters)
                or list(signature.parameters.values())[k + 1].kind is not _P.POSITIONAL_ONLY):
            parts.append("/")
    body = "    _kw = {}\n" + "".join(
        f"    if {n} is not {d}:\n        _kw[{n!r}] = {n}\n" for n, d in optional)
    call.append("**_kw")
    source = f"def {name}({', '.join(parts)}):\n{body}    return _native({', '.join(call)})\n"
    exec(compile(source, f"<sfit signature of {qualname}>", "exec"), namespace)
    f = namespace[name]
    f.__qualname__ = qualname
    f.__module__ = "sfit"
    f.__doc__ = doc
    return f


def with_fit_keywords(signature):
    """`signature` with its **kwargs replaced by the fit options as keyword-only parameters
    (those already positional, e.g. fit()'s tol, stay where they are)."""
    params = [p for p in signature.parameters.values() if p.kind is not _P.VAR_KEYWORD]
    names = {p.name for p in params}
    for name, default in fit_keywords():
        if name not in names:
            params.append(_P(name, _P.KEYWORD_ONLY, default=default))
    return signature.replace(parameters=params)


def _is_native_method(value):
    return type(value).__name__ in ("instancemethod", "builtin_function_or_method")


def install(module, classes, functions, fit_like):
    """Replaces the public functions of `module` named in `functions` and the public methods
    (and __call__, __init__) of `classes` by Python functions with their true signatures.
    `fit_like`: names ("fit", "IncrementalFit.__init__") whose **kwargs are the fit options."""
    for name in functions:
        native = getattr(module, name)
        sig = native_signature(native)
        if name in fit_like:
            sig = with_fit_keywords(sig)
        setattr(module, name, make_function(native, name, name, sig, native_doc(native)))
    for cls in classes:
        for name, value in list(vars(cls).items()):
            if name.startswith("_") and name not in ("__call__", "__init__"):
                continue
            static = isinstance(value, staticmethod)
            native = value.__func__ if static else value
            if not _is_native_method(native):
                continue
            qualname = f"{cls.__name__}.{name}"
            sig = native_signature(native)
            if qualname in fit_like:
                sig = with_fit_keywords(sig)
            f = make_function(native, name, qualname, sig, native_doc(native))
            setattr(cls, name, staticmethod(f) if static else f)


Curvature = collections.namedtuple("Curvature", "gaussian mean k1 k2")
Curvature.__doc__ = """Curvature of a surface with respect to its unit normal S_u x S_v.

gaussian = k1 * k2, mean = (k1 + k2) / 2, k1 >= k2 the principal curvatures. A surface that
bends away from its normal has negative normal curvature: a sphere with an outward normal
has mean -1/R, Gaussian 1/R**2. NaN where S_u x S_v vanishes."""
Curvature.__module__ = "sfit"


def curvature(self, u, v, grid=False, threads=0):
    """Gaussian, mean and principal curvatures, from one basis evaluation per point.

    u, v, grid, threads: as __call__. Returns a Curvature (gaussian, mean, k1, k2) of
    arrays shaped (n,) ((len(u), len(v)) with grid=True), or of numbers for two numbers.
    """
    c = self._curvature(u, v, grid, threads)
    parts = [c[..., k] for k in range(4)]
    if c.ndim == 1:
        parts = [float(x) for x in parts]
    return Curvature(*parts)


curvature.__qualname__ = "Surface.curvature"
curvature.__module__ = "sfit"

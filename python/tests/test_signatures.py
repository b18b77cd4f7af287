"""Public signatures show their real defaults, and the stubs (__init__.pyi) say the same."""

import ast
import inspect
import pathlib

import pytest

import persson_check

STUBS = pathlib.Path(persson_check.__file__).with_name("__init__.pyi")

FUNCTIONS = [
    name for name in persson_check.__all__ if inspect.isroutine(getattr(persson_check, name))
]
CLASSES = [name for name in persson_check.__all__ if inspect.isclass(getattr(persson_check, name))]


def _methods(cls):
    for name, member in vars(cls).items():
        if name.startswith("_") or not callable(member):
            continue
        try:
            yield name, inspect.signature(member)
        except (TypeError, ValueError):
            continue


def _stub_defaults(node):
    """The parameters of a stub's function: name -> its default (or the empty marker)."""
    args = node.args
    positional = args.posonlyargs + args.args
    defaults = [inspect.Parameter.empty] * (len(positional) - len(args.defaults))
    defaults += [ast.literal_eval(d) for d in args.defaults]
    out = dict(zip((a.arg for a in positional), defaults))
    for a, d in zip(args.kwonlyargs, args.kw_defaults):
        out[a.arg] = inspect.Parameter.empty if d is None else ast.literal_eval(d)
    out.pop("self", None)
    return out


def _stubs():
    tree = ast.parse(STUBS.read_text())
    functions, methods = {}, {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            functions[node.name] = _stub_defaults(node)
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and not item.name.startswith("_"):
                    methods[(node.name, item.name)] = _stub_defaults(item)
    return functions, methods


def test_the_stubs_name_every_solver_in_order():
    tree = ast.parse(STUBS.read_text())
    aliases = {
        node.targets[0].id: node.value
        for node in tree.body
        if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name)
    }
    literal = aliases["SolverName"]
    assert ast.unparse(literal.value) == "Literal"
    assert ast.literal_eval(literal.slice) == persson_check.SOLVERS
    assert len(set(persson_check.SOLVERS)) == len(persson_check.SOLVERS) >= 2


def test_every_public_function_is_listed():
    assert set(FUNCTIONS) == {
        "check_surface", "contact_area_law", "merge", "plan", "report", "solve", "surface", "sweep",
        "theory", "validate",
    }


@pytest.mark.parametrize("name", FUNCTIONS)
def test_no_ellipsis_defaults(name):
    signature = inspect.signature(getattr(persson_check, name))
    hidden = [p.name for p in signature.parameters.values() if p.default is Ellipsis]
    assert not hidden, f"{name}{signature}: defaults shown as Ellipsis: {hidden}"


def test_no_ellipsis_defaults_in_methods():
    for cls in CLASSES:
        for method, signature in _methods(getattr(persson_check, cls)):
            hidden = [p.name for p in signature.parameters.values() if p.default is Ellipsis]
            assert not hidden, f"{cls}.{method}{signature}: {hidden}"


# The defaults the library writes once (the stubs show them as `...`): the runtime
# signature must take each from the native module.
LIBRARY_DEFAULTS = {
    ("solve", "solver"): persson_check._native.DEFAULT_SOLVER,
    ("solve", "tol"): persson_check._native.DEFAULT_TOL,
    ("solve", "max_iter"): persson_check._native.DEFAULT_MAX_ITER,
    ("sweep", "solver"): persson_check._native.DEFAULT_SOLVER,
    ("sweep", "tol"): persson_check._native.DEFAULT_TOL,
    ("sweep", "max_iter"): persson_check._native.DEFAULT_MAX_ITER,
    **{
        ("check_surface", key): value
        for key, value in persson_check._native.CHECK_SURFACE_DEFAULTS.items()
    },
}


@pytest.mark.parametrize("name", FUNCTIONS)
def test_stubs_give_the_same_parameters_and_defaults(name):
    functions, _ = _stubs()
    assert name in functions, f"{name} has no stub"
    runtime = {
        p.name: p.default for p in inspect.signature(getattr(persson_check, name)).parameters.values()
    }
    stub = dict(functions[name])
    for param, default in stub.items():
        if default is Ellipsis:
            assert (name, param) in LIBRARY_DEFAULTS, f"{name}({param}=...): not a library default"
            stub[param] = LIBRARY_DEFAULTS[(name, param)]
    assert stub == runtime


def test_stubs_of_methods_give_the_same_parameters_and_defaults():
    _, methods = _stubs()
    checked = 0
    for cls in CLASSES:
        for method, signature in _methods(getattr(persson_check, cls)):
            runtime = {p.name: p.default for p in signature.parameters.values()}
            runtime.pop("self", None)
            assert methods.get((cls, method)) == runtime, f"{cls}.{method}"
            checked += 1
    assert checked >= 10


def test_help_shows_the_docs():
    for name in FUNCTIONS:
        assert getattr(persson_check, name).__doc__, name


def test_solve_error_is_named_in_the_package():
    assert persson_check.SolveError.__module__ == "persson_check"
    assert issubclass(persson_check.SolveError, RuntimeError)

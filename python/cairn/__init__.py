"""Cairn from Python: does an assembly of rigid parts stay put? (docs/python.md)

    import cairn
    m = cairn.load("examples/paper_fig1.json")
    r = cairn.check(m, without=["C"])      # the keys of `cairn check --json`
    r["stable"], r["moving"], r["contact_arrays"]["normal_force"]

Every result is the dict of the CLI's ``--json`` document for the same input,
built by the same C++ code, with numeric columns added as numpy arrays
(``contact_arrays`` of check, ``timeline`` of simulate). Solves release the
GIL, so threads can check many assemblies at once. Bad input raises
:class:`InputError` (a ``ValueError``) with the CLI's message: the file, the
JSON path and what is wrong.
"""

import io
import json
import operator
import os
import stat
import tempfile

import numpy as np

from . import _cairn
from ._cairn import InputError, Model

InputError.__module__ = Model.__module__ = "cairn"  # cairn.InputError in tracebacks

__all__ = [
    "InputError",
    "Model",
    "load",
    "from_compas",
    "check",
    "simulate",
    "plan",
    "sequence",
    "blocking",
    "margin",
    "compas_forces",
    "read_timeline",
    "plot",
]

_FORMATS = ("scene", "compas", "step", "asap")
_INTERFACES = ("detect", "stored")

# The whole numbers the CLI's options accept (src/cli/main.cpp), for the
# keywords that are those options: (least, most).
_INT_MAX = 2**31 - 1  # the C++ int they are passed as
_MAX_FIXELS = (1, 20)  # simulate --max-fixels
_ALLOW_FIXTURES = (0, 20)  # plan --allow-fixtures
_NON_NEGATIVE = (0, _INT_MAX)  # plan --max, --threads
_MAX_TICKS = (0, 2**63 - 1)  # simulate --max-ticks (a C++ long long)
_MAX_INPUT_SIZE = (1, 2**64 - 1)  # --max-input-size, bytes


def __getattr__(name):
    # cairn.plot on first use (it imports matplotlib only when it draws), so
    # that `python3 -m cairn.plot` does not find it imported already.
    if name == "plot":
        import importlib
        return importlib.import_module(".plot", __name__)
    raise AttributeError(f"module 'cairn' has no attribute {name!r}")


def _input_error(where, message, file=""):
    """An InputError raised by the Python half, with the attributes the
    compiled half's have: `where` is the argument (as the JSON path)."""
    e = InputError(": ".join(x for x in (file, where, message) if x))
    e.file, e.json_path, e.message = file, where, message
    return e


def _whole(value, what, limits):
    """A whole-number keyword argument (an int, a numpy integer, or a float
    with a whole value; not a bool) within `limits` (least, most), as the
    CLI's option of the same name accepts; else an InputError naming it."""
    lo, hi = limits
    wanted = (f"a whole number from {lo} to {hi}" if hi < _INT_MAX
              else f"a whole number ≥ {lo}")
    if isinstance(value, (bool, np.bool_)):
        raise _input_error(what, f"must be {wanted}, not {value!r}")
    try:
        number = operator.index(value)
    except TypeError:
        if isinstance(value, (float, np.floating)) and float(value).is_integer():
            number = int(value)
        else:
            raise _input_error(what, f"must be {wanted}, not {value!r}") from None
    if number < lo or number > hi:
        raise _input_error(what, f"must be {wanted} (got {number})")
    return number


def _flag(value, what):
    """A yes/no keyword argument: a bool (or numpy bool, or 0 or 1); else an
    InputError naming it."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)) and value in (0, 1):
        return bool(value)
    raise _input_error(what, f"must be True or False, not {value!r}")


def _number(value, what):
    """A real-number keyword argument as a float; else an InputError naming
    it (whether the number is allowed is the C++ side's to say, as the CLI's)."""
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise _input_error(what, f"must be a number, not {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise _input_error(what, f"must be a number, not {value!r}") from None


def _numbers(value, what):
    """A sequence of numbers (a vector) as a list of floats; [] for None;
    else an InputError naming the keyword."""
    if value is None:
        return []
    if isinstance(value, (str, bytes)):
        raise _input_error(what, f"must be a sequence of numbers, not {value!r}")
    try:
        items = list(value)
    except TypeError:
        raise _input_error(what, f"must be a sequence of numbers, not {value!r}") from None
    return [_number(x, what) for x in items]


def _names(value, what):
    """A list of part names from None, a name, or an iterable of names (ints
    are COMPAS node keys)."""
    if value is None:
        return []
    if isinstance(value, (str, int)):
        value = [value]
    names = []
    for v in value:
        if not isinstance(v, (str, int)) or isinstance(v, bool):
            raise TypeError(f"{what}: part names are strings (or COMPAS node keys), not {v!r}")
        names.append(str(v))
    return names


def _pairs(pairs, what):
    """Pairs of part names for fastened/touching: "A:B" strings or (A, B)
    tuples, as "A:B"."""
    out = []
    for p in pairs or ():
        if isinstance(p, str):
            out.append(p)
        elif isinstance(p, (tuple, list)) and len(p) == 2:
            out.append(":".join(_names(p, what)))
        else:
            raise TypeError(f"{what}: a pair of part names is 'A:B' or (A, B), not {p!r}")
    return out


def _model_options(friction, supports, gravity, tolerance, interfaces, mesh_tolerance=None,
                   sidecar=None, max_input_size=None, fastened=None, touching=None,
                   overlap_depth=None):
    if interfaces not in _INTERFACES:
        raise _input_error("interfaces", f"must be one of {_INTERFACES}, not {interfaces!r}")
    return dict(
        friction=None if friction is None else _number(friction, "friction"),
        supports=_names(supports, "supports"),
        gravity=_numbers(gravity, "gravity"),
        tolerance=None if tolerance is None else _number(tolerance, "tolerance"),
        overlap_depth=None if overlap_depth is None else _number(overlap_depth, "overlap_depth"),
        interfaces=interfaces,
        mesh_tolerance=None if mesh_tolerance is None else _number(mesh_tolerance,
                                                                   "mesh_tolerance"),
        sidecar="" if sidecar is None else os.fspath(sidecar),
        fastened=_pairs(fastened, "fastened"),
        touching=_pairs(touching, "touching"),
        max_input_size=(_cairn.DEFAULT_MAX_INPUT_SIZE if max_input_size is None
                        else _whole(max_input_size, "max_input_size", _MAX_INPUT_SIZE)),
    )


def load(file, format="scene", friction=None, supports=None, gravity=None, tolerance=None,
         interfaces="detect", mesh_tolerance=None, sidecar=None, max_input_size=None,
         fastened=None, touching=None, overlap_depth=None):
    """Reads a model from a file, as the CLI does: ``format`` "scene" (scene
    format 1), "compas" (a COMPAS assembly, which needs ``friction``), "step"
    (a STEP assembly) or "asap" (an ASAP assembly folder), and the model
    options ``friction``, ``supports`` (parts fixed in addition), ``gravity``
    (2 or 3 numbers), ``tolerance``, ``interfaces`` ("detect" or "stored"),
    ``mesh_tolerance`` (STEP's chordal tolerance, metres), ``sidecar`` (STEP
    and ASAP: a file with what the model does not carry),
    ``max_input_size`` (bytes), ``fastened`` and ``touching`` (STEP: pairs of
    parts, "A:B" or (A, B), joined into one rigid part, or made to touch
    where they overlap) and ``overlap_depth`` (3-D: how deep parts meant to
    touch may overlap, read as contact on the overlap's mid-surface; the
    pairs so read are ``Model.overlaps``) of ``--friction`` ...
    ``--overlap-depth``.
    Raises InputError."""
    if format not in _FORMATS:
        raise _input_error("format", f"must be one of {_FORMATS}, not {format!r}")
    return _cairn.load(os.fspath(file), format,
                       _model_options(friction, supports, gravity, tolerance, interfaces,
                                      mesh_tolerance, sidecar, max_input_size, fastened,
                                      touching, overlap_depth))


def _write_outputs(m, files, inputs=()):
    """Writes [(path, text, keyword)] as the CLI writes its outputs: never over
    the model's file or another input of the call (`inputs`: a plan, a paths
    file), each whole or not at all (a temporary file beside it, renamed); a
    path that cannot be written is an InputError naming it."""
    for path, text, keyword in files:
        path = os.fspath(path)
        if not isinstance(path, str) or not path:
            raise _input_error(keyword, f"must be a file name, not {path!r}")
        for given in (m.file, *inputs):
            if os.path.exists(path) and os.path.exists(given) and os.path.samefile(path, given):
                raise _input_error(keyword, f"is the input file {given!r}: it would be replaced")
        tmp = None
        try:
            fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)),
                                       prefix=".cairn-", suffix=".tmp")
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(text)
            os.replace(tmp, path)
            tmp = None
        except (OSError, ValueError) as e:
            raise _input_error(keyword, f"cannot write {path!r}: "
                               f"{getattr(e, 'strerror', None) or e}") from None
        finally:
            if tmp is not None and os.path.exists(tmp):
                os.unlink(tmp)


def _plain(data):
    """A COMPAS assembly (an object with ``__data__`` or ``to_data()``, or its
    data) as plain JSON data: what ``compas.json_dumps`` writes."""
    if isinstance(data, (str, bytes)):
        raise TypeError("from_compas takes the assembly's data (a dict), not text: "
                        "json.load the file, or use cairn.load(file, format='compas')")
    try:
        import compas  # noqa: F401  (only to serialise COMPAS objects)
        if not isinstance(data, dict) or _has_objects(data):
            return json.loads(compas.json_dumps(data))
    except ImportError:
        pass
    if not isinstance(data, dict) and hasattr(data, "__data__"):
        data = data.__data__
    elif not isinstance(data, dict) and hasattr(data, "to_data"):
        data = data.to_data()
    return data


def _has_objects(value):
    if isinstance(value, dict):
        return any(_has_objects(v) for v in value.values())
    if isinstance(value, (list, tuple)):
        return any(_has_objects(v) for v in value)
    return hasattr(value, "__data__")


def _json_default(value):
    # numpy numbers and arrays, and anything COMPAS-like, as JSON.
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if hasattr(value, "__data__"):
        return {"dtype": getattr(value, "__dtype__", type(value).__name__), "data": value.__data__}
    raise TypeError(f"not JSON data: {value!r}")


def _dumps(data):
    return json.dumps(data, default=_json_default, allow_nan=True)


def from_compas(assembly_data, friction=None, supports=None, gravity=None, tolerance=None,
                interfaces="detect", name="assembly_data"):
    """The model of a COMPAS block assembly given as data: the dict of
    ``json.load`` of its file (or ``assembly.__data__`` / ``to_data()``, or the
    assembly itself when COMPAS is installed). ``friction`` is required (COMPAS
    files store none; compas_cra's examples use 0.84); ``supports`` names
    blocks by their node keys. Messages name the document ``name``."""
    text = _dumps(_plain(assembly_data))
    return _cairn.from_compas(text, name,
                              _model_options(friction, supports, gravity, tolerance, interfaces))


def _check_model(m):
    if not isinstance(m, Model):
        raise TypeError(f"expected a cairn.Model (cairn.load, cairn.from_compas), not {type(m)}")


def _normalize(normalize):
    if normalize is None:
        return ""
    return str(normalize)


def check(m, without=None, normalize=None, html=None, rule="loaded-from-rest"):
    """``cairn check --json``: is the assembly, with the parts ``without``
    taken away, stable? ``rule`` (``--rule``) decides where rigid bodies leave
    it open: ``"loaded-from-rest"`` (the default) or ``"equilibrium"``; the
    dict's ``stability`` says whether strong stability is proved (what
    ``--require strong`` asks). The dict has the CLI's keys, plus ``contact_arrays``
    (numpy columns of ``contacts``: ``point`` (n, d), ``normal`` (n, d),
    ``normal_force`` (n,), ``friction_force`` ((n,) in 2-D, (n, 3) in 3-D),
    ``parts`` (n, 2) part indices into ``m.parts``, -1 for the world).
    ``normalize`` names the part whose weight is the force unit; ``html``, a
    file to write the result page to (``--html``)."""
    _check_model(m)
    doc, _, page, *_ = _cairn.check(m, _names(without, "without"), _normalize(normalize),
                                    html is not None, str(rule))
    if html is not None:
        _write_outputs(m, [(html, page, "html")])
    doc = json.loads(doc)
    doc["contact_arrays"] = _contact_arrays(m, doc)
    return doc


def _contact_arrays(m, doc):
    contacts = doc["contacts"]
    dim = doc["dimension"]
    index = {name: i for i, name in enumerate(m.parts)}
    n = len(contacts)
    friction_shape = (n,) if dim == 2 else (n, 3)
    return {
        "point": np.array([c["point"] for c in contacts], dtype=float).reshape(n, dim),
        "normal": np.array([c["normal"] for c in contacts], dtype=float).reshape(n, dim),
        "normal_force": np.array([c["normal_force"] for c in contacts], dtype=float),
        "friction_force": np.array([c["friction_force"] for c in contacts],
                                   dtype=float).reshape(friction_shape),
        "parts": np.array([[index.get(p, -1) for p in c["parts"]] for c in contacts],
                          dtype=np.int64).reshape(n, 2),
    }


def simulate(m, plan, continue_after_failure=False, normalize=None, suggest_fixtures=False,
             max_fixels=3, max_ticks=None, margin=None, html=None, timeline=None):
    """``cairn simulate --json``: runs a plan (a plan file, or a plan as a
    dict) along its paths. The dict has the CLI's keys, plus ``timeline``: the
    ``--timeline`` CSV as a dict of numpy columns named by its header (one
    entry per tick and contact point; :func:`cairn.plot.timeline` sums them per
    pair or patch). With ``suggest_fixtures`` the key ``fixtures`` as the CLI's
    ``--suggest-fixtures``; ``max_ticks`` is ``--max-ticks`` (None: the CLI's
    default); ``margin="friction"`` adds the key ``margin`` as ``--margin
    friction``; ``html`` and ``timeline`` are files to write the result page
    and the timeline CSV to."""
    _check_model(m)
    if isinstance(plan, dict):
        plan_file, plan_text = "plan", _dumps(plan)
    else:
        plan_file, plan_text = os.fspath(plan), ""
    if margin not in (None, "friction"):
        raise _input_error("margin", f"must be None or 'friction', not {margin!r}")
    doc_text, _, page, csv, *_ = _cairn.simulate(
        m, plan_file, plan_text, _flag(continue_after_failure, "continue_after_failure"),
        _normalize(normalize), _flag(suggest_fixtures, "suggest_fixtures"),
        _whole(max_fixels, "max_fixels", _MAX_FIXELS),
        _cairn.DEFAULT_MAX_TICKS if max_ticks is None
        else _whole(max_ticks, "max_ticks", _MAX_TICKS),
        margin or "", html is not None)
    outputs = []
    if html is not None:
        outputs.append((html, page, "html"))
    if timeline is not None:
        outputs.append((timeline, csv, "timeline"))
    _write_outputs(m, outputs, [plan_file] if not plan_text else [])
    doc = json.loads(doc_text)
    doc["timeline"] = read_timeline(io.StringIO(csv))
    return doc


def plan(m, max=None, single_parts=False, paths=None, allow_fixtures=0, keep=None,
         support="full", threads=0, dt=None, speed=None, directions="ndbg", html=None, dot=None,
         emit_plans=None):
    """``cairn plan --json``: stable disassembly sequences. ``max``: stop after
    this many (best-first; None: all); ``single_parts``: no subassemblies;
    ``paths``: candidate paths (a file, or its contents as a dict);
    ``allow_fixtures``: up to this many fixels where nothing is stable;
    ``keep``: parts never removed; ``support``: "full", "none" or "both";
    ``dt``, ``speed``: the paths' time step and speed (None: automatic);
    ``directions``: "ndbg" (the NDBG's cells) or "axes" (±x, ±y, ±z);
    ``html``, ``dot``: files to write the result page and the graph to;
    ``emit_plans``: a folder to write every sequence's plan files to."""
    _check_model(m)
    options = dict(
        max=0 if max is None else _whole(max, "max", _NON_NEGATIVE),
        single_parts=_flag(single_parts, "single_parts"),
        allow_fixtures=_whole(allow_fixtures, "allow_fixtures", _ALLOW_FIXTURES),
        keep=_names(keep, "keep"), support=str(support),
        threads=_whole(threads, "threads", _NON_NEGATIVE),
        dt=0.0 if dt is None else _number(dt, "dt"),
        speed=0.0 if speed is None else _number(speed, "speed"),
        directions=str(directions), page=html is not None, dot=dot is not None,
        emit_plans=emit_plans is not None, paths="")
    for key, given in (("dt", dt), ("speed", speed)):
        if given is not None and not 0 < options[key] < float("inf"):
            raise _input_error(key, f"must be a positive number (or None: automatic), "
                                    f"not {given!r}")
    if isinstance(paths, dict):
        # The candidate-paths reader reads files: the dict goes through one.
        with tempfile.TemporaryDirectory() as tmp:
            options["paths"] = os.path.join(tmp, "paths.json")
            with open(options["paths"], "w", encoding="utf-8") as f:
                f.write(_dumps(paths))
            answer = _cairn.plan(m, options)
    else:
        options["paths"] = "" if paths is None else os.fspath(paths)
        answer = _cairn.plan(m, options)
    doc, _, page, _, graph, plans = answer
    outputs = []
    if html is not None:
        outputs.append((html, page, "html"))
    if dot is not None:
        outputs.append((dot, graph, "dot"))
    outputs += _plan_files(emit_plans, plans)
    _write_outputs(m, outputs, [] if paths is None or isinstance(paths, dict) else [paths])
    return json.loads(doc)


def _plan_files(emit_plans, plans):
    """The ``emit_plans`` folder (made now) and the plan files to write in it,
    as _write_outputs takes them; none when ``emit_plans`` is None."""
    if emit_plans is None:
        return []
    folder = os.fspath(emit_plans)
    try:
        os.makedirs(folder, exist_ok=True)
    except (OSError, ValueError) as e:
        raise _input_error("emit_plans", f"cannot make the folder {folder!r}: "
                           f"{getattr(e, 'strerror', None) or e}") from None
    return [(os.path.join(folder, name), text, "emit_plans") for name, text in plans]


def sequence(m, temporary="hold", max_temporary=None, direction=None, directions="up", beam=4,
             rule="loaded-from-rest", require=None, time_limit=None, emit_plans=None, html=None,
             threads=0):
    """``cairn sequence --json``: an order to build the model in, one part a
    step from its fixed parts up, every state standing, with the fewest
    temporary holds in place at once and a lower bound that proves how far
    that is from the fewest (docs/sequence.md). ``max_temporary``: the most
    holds at once (None: no bound); ``direction``: the one removal direction
    (2 or 3 numbers; a part arrives along its reverse); ``directions``: "up"
    (against gravity), "axes" or "ndbg"; ``beam``: states kept per step; ``rule``
    and ``require`` as ``check``'s; ``time_limit``: seconds, then the best
    order so far (``stopped``); ``emit_plans``: a folder to write the order to
    as an assembly plan with its holds (sequence.assemble.plan.json, for
    ``simulate``); ``html``: a file to write the result page to (the build
    played step by step with its supports); ``threads``: 0 for every core. The dict has the CLI's keys."""
    _check_model(m)
    d = _numbers(direction, "direction")
    limit = 0.0 if time_limit is None else _number(time_limit, "time_limit")
    if time_limit is not None and not 0 < limit < float("inf"):
        raise _input_error("time_limit", f"must be a positive number of seconds (or None), "
                                         f"not {time_limit!r}")
    options = dict(
        temporary=str(temporary),
        max_temporary=-1 if max_temporary is None else _whole(max_temporary, "max_temporary",
                                                              _NON_NEGATIVE),
        direction=d, directions=str(directions), beam=_whole(beam, "beam", (1, 1000)),
        threads=_whole(threads, "threads", _NON_NEGATIVE),
        rule=str(rule), require="" if require is None else str(require), time_limit=limit,
        emit_plans=emit_plans is not None, page=html is not None)
    doc, _, page, _, _, plans = _cairn.sequence(m, options)
    outputs = [(html, page, "html")] if html is not None else []
    _write_outputs(m, outputs + _plan_files(emit_plans, plans), [])
    return json.loads(doc)


def blocking(m, direction=None, without=None, html=None):
    """``cairn blocking --json``: the nondirectional blocking graph. With a
    ``direction`` (2 numbers in 2-D, 3 in 3-D), ``cairn blocking --json
    --direction``: ``cells`` holds the one cell at that direction, which parts
    can leave along it and which block which. ``html``: a file to write the
    result page to (``--html``: the cells one at a time on the drawing)."""
    _check_model(m)
    d = []
    if direction is not None:
        d = _numbers(direction, "direction")
        if len(d) != m.dimension and not (m.dimension == 2 and len(d) == 3):
            raise _input_error("direction", f"must have {m.dimension} numbers in a "
                                            f"{m.dimension}-D scene, not {len(d)}")
        if len(d) == 2:
            d.append(0.0)  # the command's X,Y,Z
    doc, _, page, *_ = _cairn.blocking(m, _names(without, "without"), d, html is not None)
    if html is not None:
        _write_outputs(m, [(html, page, "html")])
    return json.loads(doc)


def margin(m, friction=False, tilt=None, load=None, point=None, direction=None, without=None,
           rule="loaded-from-rest", html=None):
    """``cairn margin --json``: how far from failing the assembly (with the
    parts ``without`` taken away) is, one quantity at a time:
    ``friction=True``, the least friction (μ*, or the factor k* on every
    friction pair) at which it stands; ``tilt=(x, y, z)``, the critical tilts
    about that axis in each sense (``critical_deg``); ``load="PART"`` with
    ``point`` and ``direction`` (2 or 3 numbers each), the largest force
    along the direction at the point that the part carries. The model's own
    μ is the one it was loaded with (``cairn.load(..., friction=...)``).
    ``rule`` (``--rule``, as in ``check``) is the verdict whose threshold
    ``verdict_critical`` and ``stands_at_nominal`` give. The dict has the
    CLI's keys (docs/margin.md); its ``margin`` holds the answer. ``html``:
    a file to write the result page to (``--html``: each component's
    equilibrium at its critical value, the mechanism just past it animated).
    Raises InputError for no quantity or two, an unknown or fixed part, or a
    wrong count of numbers."""
    _check_model(m)
    doc, _, page, *_ = _cairn.margin(m, _flag(friction, "friction"), _numbers(tilt, "tilt"),
                                     "" if load is None else str(load), _numbers(point, "point"),
                                     _numbers(direction, "direction"),
                                     _names(without, "without"), str(rule), html is not None)
    if html is not None:
        _write_outputs(m, [(html, page, "html")])
    return json.loads(doc)


_INT_COLUMNS = ("step", "tick", "patch")
_BOOL_COLUMNS = ("breaks", "slides")
_NAME_COLUMNS = ("part_a", "part_b")


def read_timeline(source):
    """A ``--timeline`` CSV (a path, or a file object) as a dict of numpy
    columns named by its header: ``time`` and the forces as floats, ``step``,
    ``tick`` (and ``patch`` in 3-D) as ints, ``breaks``/``slides`` as bools,
    ``part_a``/``part_b`` as strings. One entry per tick and contact point."""
    if isinstance(source, (str, os.PathLike)):
        # As Cairn's readers open a file (io/input_file.h): a regular file
        # only, never a FIFO (which would block) or a device (never ending).
        try:
            if not stat.S_ISREG(os.stat(source).st_mode):
                raise _input_error("", "is not a regular file (a folder, a FIFO or a device)",
                                   file=str(source))
            f = open(source, encoding="utf-8")
        except OSError as e:
            raise _input_error("", f"cannot read the file: {e.strerror}", file=str(source)) from None
        except ValueError as e:  # a NUL byte in the name
            if isinstance(e, InputError):
                raise
            raise _input_error("", "cannot read the file: its name has a NUL byte",
                               file=repr(str(source))) from None
        with f:
            return read_timeline(f)
    if not callable(getattr(source, "readline", None)):
        raise TypeError("read_timeline takes a path or a text file object, not "
                        f"{type(source).__name__}")
    name = str(getattr(source, "name", "timeline"))
    not_csv = ("not a Cairn timeline CSV (`cairn simulate --timeline`: its header starts "
               "with 'time')")
    try:
        header = source.readline().strip().split(",")
        if header[0] != "time":
            raise ValueError
        rows = [line.rstrip("\n").split(",") for line in source if line.strip()]
    except (UnicodeDecodeError, ValueError, TypeError):  # TypeError: a binary file
        raise _input_error("", not_csv, file=name) from None
    for n, row in enumerate(rows, start=2):
        if len(row) != len(header):
            raise _input_error(f"line {n}", f"{len(row)} fields where the header has "
                               f"{len(header)}", file=name)
    columns = {}
    for k, column in enumerate(header):
        values = [r[k] for r in rows]
        try:
            if column in _NAME_COLUMNS:
                columns[column] = np.array(values, dtype=str)
            elif column in _INT_COLUMNS:
                columns[column] = np.array(values, dtype=np.int64)
            elif column in _BOOL_COLUMNS:
                columns[column] = np.array([v == "1" for v in values], dtype=bool)
            else:
                columns[column] = np.array(values, dtype=float)
        except (ValueError, OverflowError):
            raise _input_error(column, "a value that is not a number of this column",
                               file=name) from None
    return columns


def compas_forces(assembly_data, r):
    """The COMPAS assembly data with Cairn's contact forces written where
    compas_cra writes its own: each stored interface's ``forces``, one
    ``{"c_np", "c_nn", "c_u", "c_v"}`` per interface point (the force on
    block v of edge (u, v) is (c_np - c_nn) n + c_u xaxis + c_v yaxis, n the
    interface's normal from u to v). ``r`` is :func:`check`'s result for the
    same assembly (``from_compas`` of this data, best with
    ``interfaces="stored"``: then every contact is an interface point). The
    data given is not changed: a copy is returned. Raises InputError (a
    ValueError) when the data are not a COMPAS assembly's, when they store no
    interfaces, or when a contact that carries force is not at a point of a
    stored interface; TypeError when ``r`` is not a dict."""
    from ._compas import fill_forces
    if not isinstance(r, dict):
        raise TypeError(f"compas_forces: r is the dict cairn.check returns, not {type(r).__name__}")
    for key in ("dimension", "contacts", "tolerances"):
        if key not in r:
            raise _input_error("r", f"not a result of cairn.check (it has no {key!r})")
    data = _plain(assembly_data)
    try:
        return fill_forces(data, r)
    except InputError:
        raise
    except ValueError as e:  # what fill_forces says of data that do not match r
        raise _input_error("", str(e)) from None
    except (KeyError, IndexError, TypeError, AttributeError) as e:
        raise _input_error("assembly_data", "not the COMPAS assembly data of this result "
                           f"(at {type(e).__name__}: {e})") from None

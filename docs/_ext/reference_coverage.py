"""Fails the build where the reference would have a name without a description.

- C++: every public function, class, struct and enum Doxygen finds in include/gpugeom (namespace
  gpugeom and the namespaces in it, not `detail`) must carry a comment (/// or ///<). Members of
  a struct are its fields: their comments are welcome, not required.
- Python: every name in the public ``__all__`` of gpugeom and its public modules, and every
  public method and property of those classes, must have a docstring, and every such name must
  appear in the Python domain of the built site (an autodoc entry).

Each gap is a Sphinx warning, so the -W build stops on it and names what lacks a description.
"""
import functools
import importlib
import inspect
import xml.etree.ElementTree as ET
from pathlib import Path

from sphinx.util import logging

log = logging.getLogger(__name__)
PY_MODULES = ["gpugeom", "gpugeom.spatial", "gpugeom.ndimage", "gpugeom.cvd", "gpugeom.mesh",
              "gpugeom.verify", "gpugeom.cells", "gpugeom.dask"]


def _described(el):
    for tag in ("briefdescription", "detaileddescription"):
        d = el.find(tag)
        if d is not None and "".join(d.itertext()).strip():
            return True
    return False


def cpp_gaps(xml_dir):
    """(kind, name) of the public C++ entities without a description."""
    xml_dir = Path(xml_dir)
    index = ET.parse(xml_dir / "index.xml").getroot()
    gaps = []
    for comp in index.findall("compound"):
        kind, refid = comp.get("kind"), comp.get("refid")
        name = comp.findtext("name")
        if kind not in ("namespace", "class", "struct") or not name.startswith("gpugeom"):
            continue
        if "detail" in name.split("::"):
            continue
        root = ET.parse(xml_dir / f"{refid}.xml").getroot().find("compounddef")
        if kind in ("class", "struct") and not _described(root):
            gaps.append((kind, name))
        for sec in root.findall("sectiondef"):
            if sec.get("kind", "").startswith(("private", "protected")):
                continue
            for m in sec.findall("memberdef"):
                mk = m.get("kind")
                if mk not in ("function", "enum", "typedef") or m.get("prot") != "public":
                    continue
                if kind in ("class", "struct") and mk == "function":
                    mname = m.findtext("name")
                    # constructors, destructors and operators of a documented class
                    if mname in (name.split("::")[-1], "~" + name.split("::")[-1]) or \
                            mname.startswith("operator"):
                        continue
                if not _described(m):
                    gaps.append((mk, f"{name}::{m.findtext('name')}"))
    return gaps


def python_names():
    for modname in PY_MODULES:
        mod = importlib.import_module(modname)
        for n in getattr(mod, "__all__", []):
            obj = getattr(mod, n)
            if isinstance(obj, (str, int, float)) or inspect.ismodule(obj):
                continue
            yield f"{getattr(obj, '__module__', modname)}.{n}", modname, n, obj


def check_cpp(app):
    xml_dir = app.config.breathe_projects[app.config.breathe_default_project]
    for kind, name in cpp_gaps(xml_dir):
        log.warning(f"C++ reference: {kind} {name} has no description (a /// comment in its "
                    f"header)")


def check_python(app, exception):
    if exception is not None or app.builder.name != "html":
        return
    documented = set(app.env.get_domain("py").objects)
    seen = set()
    for full, modname, n, obj in python_names():
        if id(obj) in seen:
            continue
        seen.add(id(obj))
        if not (getattr(obj, "__doc__", None) or "").strip():
            log.warning(f"Python reference: {modname}.{n} has no docstring")
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for attr, v in vars(obj).items():  # its public methods and properties
                if attr.startswith("_") or not (inspect.isfunction(v) or isinstance(
                        v, (property, functools.cached_property, staticmethod, classmethod))):
                    continue
                f = v.fget if isinstance(v, property) else getattr(v, "__func__", v)
                if not (getattr(f, "__doc__", None) or "").strip():
                    log.warning(f"Python reference: {modname}.{n}.{attr} has no docstring")
        names = {f"{modname}.{n}", full, f"gpugeom.{n}"}
        if not names & documented:
            log.warning(f"Python reference: {modname}.{n} is not in the API pages "
                        f"(docs/api/python.rst)")


def setup(app):
    app.connect("builder-inited", check_cpp)
    app.connect("build-finished", check_python)
    return {"version": "1", "parallel_read_safe": True}

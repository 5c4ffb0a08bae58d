"""Scene files: Wavefront OBJ (+MTL) and a subset of Mitsuba 3's XML format.

* :func:`load_obj` reads an OBJ file and its MTL materials (diffuse ``Kd`` and emitted ``Ke``)
  with `trimesh <https://trimesh.org>`_ into a :class:`~dualight.Scene`.
* :func:`load_mitsuba_xml` reads a Mitsuba 3 XML scene (the subset listed there) into a
  :class:`~dualight.Scene` with its camera; :func:`read_mitsuba_settings` returns the render
  settings the file asks for (samples per pixel, path depth, integrator).
* :func:`save_mitsuba_xml` writes any :class:`~dualight.Scene` as a Mitsuba 3 XML file with its
  meshes as binary PLY files beside it; ``mitsuba.load_file`` renders it exactly as
  ``mitsuba.load_dict(scene.to_mitsuba(...))`` does.

Everything a loader does not support raises a ``ValueError`` that names the element, the file
and what is supported, rather than being dropped silently; a missing file raises
``FileNotFoundError``. The few approximations that are accepted (a ``conductor`` that is not a
perfect mirror, a pixel filter other than ``box``, smooth vertex normals) warn with a
``UserWarning``.
"""

from dualight.io.mitsuba_writer import save_mitsuba_xml
from dualight.io.mitsuba_xml import load_mitsuba_xml, read_mitsuba_settings
from dualight.io.obj import load_obj

__all__ = ["load_mitsuba_xml", "load_obj", "read_mitsuba_settings", "save_mitsuba_xml"]

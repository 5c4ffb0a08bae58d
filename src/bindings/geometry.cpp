#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "bindings/emitters.h"
#include "bindings/materials.h"
#include "bindings/numpy_util.h"
#include "bindings/textures.h"
#include "core/parallel.h"
#include "geometry/camera.h"
#include "geometry/scene.h"

namespace dualight::bindings {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<uint32_t, py::array::c_style | py::array::forcecast>;

Vec3 to_vec3(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

// Per material: (BSDF parameter name, texture) pairs.
using MaterialTextures = std::vector<std::pair<std::string, TextureObject>>;

void add_textures(const std::vector<MaterialTextures>& textures, std::vector<Material>& materials) {
  if (textures.size() != materials.size()) {
    throw py::value_error("textures needs one list per material (" + std::to_string(materials.size()) + ")");
  }
  for (size_t i = 0; i < materials.size(); ++i) {
    for (const auto& [name, t] : textures[i]) {
      const BsdfParameter p = bsdf_parameter(name);
      if (!has_parameter(materials[i].bsdf, p)) {
        throw py::value_error("material " + std::to_string(i) + ": its BSDF has no texturable '" + name + "'");
      }
      materials[i].textures.push_back({p, t.texture});
    }
  }
}

// Per material: its radiance texture or None.
void add_emission_textures(const std::vector<std::optional<TextureObject>>& textures, std::vector<Material>& materials) {
  if (textures.size() != materials.size()) {
    throw py::value_error("emission_textures needs one entry per material (" + std::to_string(materials.size()) + ")");
  }
  for (size_t i = 0; i < materials.size(); ++i) {
    if (textures[i]) materials[i].emission_texture = textures[i]->texture;
  }
}

// One material per row of reflectance/emission. `kind` (BsdfKind values) and `ior` are optional
// so that diffuse-only callers (radiosity patches) need not pass them.
std::shared_ptr<Scene> make_scene(const FloatArray& positions, const IndexArray& triangles,
                                  const IndexArray& material_of, const FloatArray& reflectance,
                                  const FloatArray& emission, const std::optional<IndexArray>& kind,
                                  const std::optional<FloatArray>& ior,
                                  const std::optional<std::vector<BsdfObject>>& bsdfs,
                                  const std::optional<FloatArray>& normals, const std::optional<FloatArray>& uvs,
                                  const std::optional<std::vector<MaterialTextures>>& textures,
                                  const std::optional<std::vector<EmitterObject>>& emitters,
                                  const std::optional<std::vector<std::optional<TextureObject>>>& emission_textures,
                                  bool robust_intersections) {
  std::vector<float> p = rows_of(positions, 3, "positions");
  std::vector<float> ns = normals ? rows_of(*normals, 3, "normals") : std::vector<float>{};
  if (normals && ns.size() != p.size()) throw py::value_error("normals needs one row per position");
  std::vector<float> uv = uvs ? rows_of(*uvs, 2, "uvs") : std::vector<float>{};
  if (uvs && uv.size() / 2 != p.size() / 3) throw py::value_error("uvs needs one row per position");
  std::vector<uint32_t> t = rows_of(triangles, 3, "triangles");
  if (material_of.ndim() != 1) throw py::value_error("material_of must be one-dimensional");
  std::vector<uint32_t> m(material_of.data(), material_of.data() + material_of.size());
  const std::vector<float> rho = rows_of(reflectance, 3, "reflectance");
  const std::vector<float> Le = rows_of(emission, 3, "emission");
  if (rho.size() != Le.size()) throw py::value_error("reflectance and emission need one row per material");
  const size_t n_materials = rho.size() / 3;
  const auto per_material = [&](const auto& a, const char* name) {
    if (a && (a->ndim() != 1 || static_cast<size_t>(a->size()) != n_materials)) {
      throw py::value_error(std::string(name) + " needs one entry per material (" + std::to_string(n_materials) + ")");
    }
  };
  per_material(kind, "kind");
  per_material(ior, "ior");
  if (bsdfs && (kind || ior)) throw py::value_error("give bsdfs or kind and ior, not both");
  if (bsdfs && bsdfs->size() != n_materials) {
    throw py::value_error("bsdfs needs one entry per material (" + std::to_string(n_materials) + ")");
  }
  std::vector<Material> materials;
  for (size_t i = 0; i < n_materials; ++i) {
    const uint32_t k = kind ? kind->data()[i] : static_cast<uint32_t>(BsdfKind::Lambertian);
    const float eta = ior ? ior->data()[i] : 1.5f;
    materials.push_back({bsdfs ? (*bsdfs)[i].bsdf : make_bsdf(k, Color(rho[3 * i], rho[3 * i + 1], rho[3 * i + 2]), eta),
                         Color(Le[3 * i], Le[3 * i + 1], Le[3 * i + 2])});
  }
  if (textures) add_textures(*textures, materials);
  if (emission_textures) add_emission_textures(*emission_textures, materials);
  std::vector<Emitter> lights;
  if (emitters) {
    for (const EmitterObject& e : *emitters) lights.push_back(e.emitter);
  }
  py::gil_scoped_release release;  // the BVH build can take a while on large meshes
  return std::make_shared<Scene>(std::move(p), std::move(t), std::move(m), std::move(materials),
                                 std::move(lights), std::move(ns), std::move(uv), robust_intersections);
}

}  // namespace

void bind_geometry(py::module_& m) {
  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene",
                                            "Immutable triangle scene committed to Embree (built by dualight.Scene).")
      .def(py::init(&make_scene), py::arg("positions"), py::arg("triangles"), py::arg("material_of"),
           py::arg("reflectance"), py::arg("emission"), py::kw_only(), py::arg("kind") = py::none(),
           py::arg("ior") = py::none(), py::arg("bsdfs") = py::none(), py::arg("normals") = py::none(),
           py::arg("uvs") = py::none(), py::arg("textures") = py::none(), py::arg("emitters") = py::none(),
           py::arg("emission_textures") = py::none(), py::arg("robust_intersections") = true,
           "Triangles with one material per row of reflectance and emission. The BSDFs: bsdfs (one "
           "dualight._core.Bsdf per material), or kind (BsdfKind values, default lambertian) and ior (a "
           "dielectric's interior IOR) as optional per-material arrays with reflectance the diffuse "
           "albedo or the mirror's reflectance. normals: optional shading normals, one row per position; a "
           "triangle is smooth-shaded when its three vertices have non-zero normals. uvs: optional surface "
           "coordinates, one row per position (NaN for meshes without). textures: per material, a list of "
           "(BSDF parameter name, Texture). emitters: point and spot lights (dualight._core.Emitter). "
           "emission_textures: per material, the Texture of its emitted radiance (an area light whose "
           "radiance varies over its surface) or None. robust_intersections: Embree's robust mode (no ray "
           "slips through where triangles meet; off, 8-19 % more samples per second but leaky, is Mitsuba "
           "3's default).")
      .def_property_readonly("triangle_count", &Scene::triangle_count)
      .def_property_readonly("robust_intersections", &Scene::robust_intersections)
      .def_property_readonly("emitter_count", &Scene::emitter_count)
      .def_property_readonly("has_hittable_emitter", &Scene::has_hittable_emitter,
                             "Whether a path can hit an emitter (an area light or an environment); false "
                             "when every emitter is a point, spot or directional light.")
      .def_property_readonly(
          "features",
          [](const Scene& s) {
            const SceneFeatures& f = s.features();
            py::dict d;
            d["specular"] = f.specular;
            d["dielectric"] = f.dielectric;
            d["all_diffuse"] = f.all_diffuse();
            d["mixed_delta"] = f.mixed_delta;
            d["emitter_triangles"] = f.emitter_triangles;
            d["closed"] = f.closed;
            d["convex_enclosure"] = f.convex_enclosure;
            d["convexity_checked"] = f.convexity_checked;
            d["unoccluded"] = f.unoccluded();
            return d;
          },
          "What the scene holds, computed once at construction (see scene_features.h).")
      .def(
          "encloses", [](const Scene& s, const std::array<float, 3>& p) { return s.features().encloses(to_vec3(p)); },
          py::arg("point"), "Whether point lies strictly inside the scene's convex enclosure (False if none).")
      .def_property_readonly("bounds",
                             [](const Scene& s) {
                               const Vec3 lo = s.bounds_min(), hi = s.bounds_max();
                               return std::make_pair(std::array<float, 3>{lo.x, lo.y, lo.z},
                                                     std::array<float, 3>{hi.x, hi.y, hi.z});
                             })
      .def(
          "intersect",
          [](const Scene& s, const FloatArray& origins, const FloatArray& directions) {
            const std::vector<float> o = rows_of(origins, 3, "origins");
            const std::vector<float> d = rows_of(directions, 3, "directions");
            if (o.size() != d.size()) throw py::value_error("origins and directions differ in length");
            const size_t n = o.size() / 3;
            std::vector<float> t(n, std::numeric_limits<float>::infinity());
            std::vector<int64_t> prim(n, -1);
            {
              py::gil_scoped_release release;
              for (size_t i = 0; i < n; ++i) {
                SurfaceHit hit;
                const Ray ray{{o[3 * i], o[3 * i + 1], o[3 * i + 2]}, {d[3 * i], d[3 * i + 1], d[3 * i + 2]}};
                if (s.intersect(ray, hit)) {
                  t[i] = hit.t;
                  prim[i] = hit.prim;
                }
              }
            }
            return py::make_tuple(to_numpy(std::move(t), {static_cast<py::ssize_t>(n)}),
                                  to_numpy(std::move(prim), {static_cast<py::ssize_t>(n)}));
          },
          py::arg("origins"), py::arg("directions"),
          "Closest hits of rays: (t, triangle index or -1); directions need not be normalised.");

  py::class_<PinholeCamera>(m, "PinholeCamera", "Pinhole camera (built by dualight.Camera).")
      .def(py::init([](const std::array<float, 3>& origin, const std::array<float, 3>& target,
                       const std::array<float, 3>& up, float fov, int width, int height) {
             return PinholeCamera(to_vec3(origin), to_vec3(target), to_vec3(up), fov, width, height);
           }),
           py::arg("origin"), py::arg("target"), py::arg("up"), py::arg("fov"), py::arg("width"),
           py::arg("height"))
      .def_property_readonly("width", &PinholeCamera::width)
      .def_property_readonly("height", &PinholeCamera::height)
      .def(
          "generate_ray",
          [](const PinholeCamera& c, float x, float y) {
            const Ray r = c.generate_ray(x, y);
            return py::make_tuple(std::array<float, 3>{r.o.x, r.o.y, r.o.z}, std::array<float, 3>{r.d.x, r.d.y, r.d.z});
          },
          py::arg("x"), py::arg("y"), "Ray (origin, unit direction) through film position (x, y) in pixels.");
}

}  // namespace dualight::bindings

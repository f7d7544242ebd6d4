// car._core: the pybind11 skin over the car_sim core. Models come back as plain dicts and lists;
// LoadError becomes car._core.LoadError (a ValueError) with the core's "file:line: element: reason" text.
#include <pybind11/pybind11.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "car_sim/mesh.hpp"
#include "car_sim/model.hpp"
#include "car_sim/plugin.hpp"
#include "car_sim/plugins.hpp"
#include "car_sim/world.hpp"
#include "geometry.hpp"
#include "materials.hpp"

namespace py = pybind11;
using namespace car_sim;

namespace {

py::list vec(const Eigen::Vector3d& v) { return py::cast(std::vector<double>{v.x(), v.y(), v.z()}); }

py::list mat(const Eigen::Matrix3d& m) {
  py::list rows;
  for (int r = 0; r < 3; ++r) rows.append(vec(m.row(r).transpose()));
  return rows;
}

py::dict pose(const Eigen::Isometry3d& T) {
  py::dict d;
  d["xyz"] = vec(T.translation());
  const Eigen::Matrix3d R = T.linear();
  // roll, pitch, yaw of R = Rz(yaw) Ry(pitch) Rx(roll)
  const double pitch = std::asin(std::max(-1.0, std::min(1.0, -R(2, 0))));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  d["rpy"] = py::cast(std::vector<double>{roll, pitch, yaw});
  d["rotation"] = mat(R);
  return d;
}

py::object opt(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::object(py::none()); }

py::list params(const ParamList& ps) {
  py::list l;
  for (const auto& kv : ps) l.append(py::make_tuple(kv.first, kv.second));
  return l;
}

py::dict shape(const Shape& s) {
  py::dict d;
  d["type"] = to_string(s.type);
  d["origin"] = pose(s.origin);
  switch (s.type) {
    case ShapeType::Box: d["size"] = vec(s.size); break;
    case ShapeType::Cylinder: d["radius"] = s.radius; d["length"] = s.length; break;
    case ShapeType::Sphere: d["radius"] = s.radius; break;
    case ShapeType::Mesh:
      d["uri"] = s.mesh_uri;
      d["scale"] = vec(s.mesh_scale);
      d["path"] = s.mesh_path;
      break;
    case ShapeType::Plane:
      d["normal"] = vec(s.normal);
      d["size"] = py::cast(std::vector<double>{s.size.x(), s.size.y()});
      break;
  }
  return d;
}

py::object inertial_dict(const std::optional<Inertial>& in) {
  if (!in) return py::none();
  py::dict d;
  d["mass"] = in->mass;
  d["origin"] = pose(in->origin);
  d["inertia"] = mat(in->inertia);
  return d;
}

py::dict plugin(const PluginSpec& p) {
  py::dict d;
  d["name"] = p.name;
  d["filename"] = p.filename;
  d["params"] = params(p.params);
  d["line"] = p.line;
  return d;
}

py::dict diagnostic(const Diagnostic& x) {
  py::dict d;
  d["severity"] = to_string(x.severity);
  d["code"] = x.code;
  d["element"] = x.element;
  d["message"] = x.message;
  d["line"] = x.line;
  return d;
}

// A LoadError as an error finding of car check: {severity, code, element, message, line}.
py::dict error_finding(const char* code, const LoadError& e) {
  py::dict err;
  err["severity"] = "error";
  err["code"] = code;
  err["element"] = e.element();
  err["message"] = e.reason();
  err["line"] = e.line();
  return err;
}

py::dict model_dict(const RobotModel& m) {
  py::dict d;
  d["name"] = m.name;
  d["source"] = m.source;
  d["root_link"] = m.root_link;
  py::list links;
  for (const auto& l : m.links) {
    py::dict ld;
    ld["name"] = l.name;
    ld["inertial"] = inertial_dict(l.inertial);
    py::list cols, vis;
    for (const auto& c : l.collisions) cols.append(shape(c));
    for (const auto& v : l.visuals) {
      py::dict vd;
      vd["name"] = v.name;
      vd["shape"] = shape(v.shape);
      py::dict md;
      md["name"] = v.material.name;
      md["rgba"] = v.material.has_rgba ? py::object(py::cast(std::vector<double>(
                                             v.material.rgba.data(), v.material.rgba.data() + 4)))
                                       : py::object(py::none());
      md["texture"] = v.material.texture;
      vd["material"] = md;
      vis.append(vd);
    }
    ld["collisions"] = cols;
    ld["visuals"] = vis;
    py::dict g;
    g["mu1"] = opt(l.gazebo.mu1);
    g["mu2"] = opt(l.gazebo.mu2);
    g["kp"] = opt(l.gazebo.kp);
    g["kd"] = opt(l.gazebo.kd);
    g["laser_retro"] = opt(l.gazebo.laser_retro);
    g["self_collide"] = l.gazebo.self_collide ? py::object(py::bool_(*l.gazebo.self_collide)) : py::object(py::none());
    g["material"] = l.gazebo.material;
    g["other"] = params(l.gazebo.other);
    ld["gazebo"] = g;
    ld["pose_in_root"] = pose(m.link_pose_in_root(l.name));
    links.append(ld);
  }
  d["links"] = links;
  py::list joints;
  for (const auto& j : m.joints) {
    py::dict jd;
    jd["name"] = j.name;
    jd["type"] = to_string(j.type);
    jd["parent"] = j.parent;
    jd["child"] = j.child;
    jd["origin"] = pose(j.origin);
    jd["axis"] = vec(j.axis);
    jd["axis_as_written"] = vec(j.axis_as_written);
    if (j.limits) {
      py::dict lim;
      lim["lower"] = j.limits->lower;
      lim["upper"] = j.limits->upper;
      lim["effort"] = j.limits->effort;
      lim["velocity"] = j.limits->velocity;
      jd["limits"] = lim;
    } else {
      jd["limits"] = py::none();
    }
    jd["damping"] = j.damping;
    jd["friction"] = j.friction;
    joints.append(jd);
  }
  d["joints"] = joints;
  py::list plugins, sensors, diags;
  for (const auto& p : m.plugins) plugins.append(plugin(p));
  for (const auto& s : m.sensors) {
    py::dict sd;
    sd["name"] = s.name;
    sd["type"] = s.type;
    sd["link"] = s.link;
    sd["pose"] = pose(s.pose);
    sd["update_rate"] = s.update_rate;
    sd["always_on"] = s.always_on;
    sd["visualize"] = s.visualize;
    sd["params"] = params(s.params);
    py::list sp;
    for (const auto& p : s.plugins) sp.append(plugin(p));
    sd["plugins"] = sp;
    sd["line"] = s.line;
    sensors.append(sd);
  }
  for (const auto& x : m.diagnostics) diags.append(diagnostic(x));
  d["plugins"] = plugins;
  d["sensors"] = sensors;
  d["diagnostics"] = diags;
  // what the URDF import lumped, dropped and anchored (docs/COMPAT-spawn.md)
  py::list lumped;
  for (const auto& l : m.lumped) {
    py::dict e;
    e["name"] = l.name;
    e["parent"] = l.parent;
    e["joint"] = l.joint;
    e["pose"] = pose(l.pose);
    e["line"] = l.line;
    lumped.append(e);
  }
  d["lumped"] = lumped;
  py::list dropped;
  for (const auto& l : m.dropped) {
    py::dict e;
    e["name"] = l.name;
    e["joint"] = l.joint;
    e["subtree"] = l.subtree;
    e["line"] = l.line;
    dropped.append(e);
  }
  d["dropped"] = dropped;
  d["world_joints"] = m.world_joints;
  return d;
}

py::dict config_dict(const ModelConfig& c) {
  py::dict d;
  py::list plugins, diags;
  for (const auto& p : c.plugins) {
    py::dict pd;
    pd["kind"] = p.kind;
    pd["name"] = p.name;
    pd["filename"] = p.filename;
    pd["sensor"] = p.sensor;
    pd["sensor_type"] = p.sensor_type;
    pd["link"] = p.link;
    py::list ps;
    for (const auto& rp : p.params) {
      py::dict r;
      r["key"] = rp.key;
      r["value"] = rp.value;
      r["unit"] = rp.unit;
      r["default"] = rp.from_default;
      ps.append(r);
    }
    pd["params"] = ps;
    plugins.append(pd);
  }
  for (const auto& x : c.diagnostics) diags.append(diagnostic(x));
  d["plugins"] = plugins;
  d["diagnostics"] = diags;
  return d;
}

py::dict state_dict(const ModelState& s) {
  py::dict d;
  d["position"] = vec(s.pose.translation());
  const Eigen::Quaterniond q(s.pose.linear());
  d["orientation"] = py::cast(std::vector<double>{q.x(), q.y(), q.z(), q.w()});
  const Eigen::Matrix3d& R = s.pose.linear();
  d["yaw"] = std::atan2(R(1, 0), R(0, 0));
  d["linear"] = vec(s.linear);
  d["angular"] = vec(s.angular);
  return d;
}

Eigen::Isometry3d pose_of(double x, double y, double z, double roll, double pitch, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

// An output's fields as a dict: numbers and text as Python scalars, short vectors as lists, bulk data as NumPy
// arrays (copied), after the fields every output starts with (robot, plugin, tick, time).
class DictVisitor : public FieldVisitor {
 public:
  DictVisitor(const Output& o, double dt) {
    d["robot"] = o.robot;
    d["plugin"] = o.plugin;
    d["tick"] = o.tick;
    d["time"] = static_cast<double>(o.tick) * dt;
  }
  void number(const char* k, double v) override { d[k] = v; }
  void integer(const char* k, int64_t v) override { d[k] = v; }
  void text(const char* k, const std::string& v) override { d[k] = v; }
  void vector(const char* k, const double* v, size_t n) override { d[k] = py::cast(std::vector<double>(v, v + n)); }
  void array(const char* k, const float* data, const std::vector<size_t>& shape) override { d[k] = make(data, shape); }
  void array(const char* k, const uint8_t* data, const std::vector<size_t>& shape) override { d[k] = make(data, shape); }
  py::dict d;

 private:
  template <class T>
  static py::array_t<T> make(const T* data, const std::vector<size_t>& shape) {
    std::vector<ssize_t> s(shape.begin(), shape.end());
    return py::array_t<T>(s, data);
  }
};

py::dict output_dict(const Output& o, double dt) {
  DictVisitor v(o, dt);
  o.visit(v);
  return v.d;
}

py::dict plugin_info_dict(const PluginInfo& s) {
  py::dict d;
  d["robot"] = s.robot;
  d["plugin"] = s.config.name;
  d["sensor"] = s.config.sensor;
  d["kind"] = s.config.kind;
  d["link"] = s.link;
  d["rate"] = s.rate;
  d["lazy"] = s.lazy;
  return d;
}

py::dict world_dict(const WorldDescription& d) {
  py::dict out;
  out["name"] = d.name;
  out["source"] = d.source;
  out["step_size"] = d.step_size;
  out["gravity"] = vec(d.gravity);
  out["sun_direction"] = vec(d.sun_direction);
  py::list models;
  for (const auto& m : d.models) {
    py::dict md;
    md["name"] = m.name;
    md["static"] = m.is_static;
    md["pose"] = pose(m.pose);
    py::list links;
    for (const auto& l : m.links) {
      py::dict ld;
      ld["name"] = l.name;
      ld["pose"] = pose(l.pose);            // in the model frame
      ld["world_pose"] = pose(m.pose * l.pose);
      ld["inertial"] = inertial_dict(l.inertial);
      py::list cols, vis;
      for (const auto& c : l.collisions) {
        py::dict cd = shape(c.shape);
        cd["name"] = c.name;
        cd["mu"] = c.friction.mu;
        cd["mu2"] = c.friction.mu2;
        cols.append(cd);
      }
      for (const auto& v : l.visuals) {
        py::dict vd = shape(v.shape);
        vd["name"] = v.name;
        vd["script"] = v.script_name;
        vd["diffuse"] = v.material.has_rgba ? py::object(py::cast(std::vector<double>(
                                                  v.material.rgba.data(), v.material.rgba.data() + 4)))
                                            : py::object(py::none());
        vd["ambient"] = v.has_ambient ? py::object(py::cast(std::vector<double>(v.ambient.data(),
                                                                               v.ambient.data() + 4)))
                                      : py::object(py::none());
        vis.append(vd);
      }
      ld["collisions"] = cols;
      ld["visuals"] = vis;
      links.append(ld);
    }
    md["links"] = links;
    models.append(md);
  }
  out["models"] = models;
  // world models simulated as robots (plug-ins, sensors, joints; docs/COMPAT-sdf.md 16), with their plug-ins
  py::list robots;
  for (const auto& r : d.robots) {
    py::dict rd;
    rd["name"] = r.name;
    rd["static"] = r.robot.is_static;
    rd["model"] = model_dict(r.robot.model);
    try {
      rd["config"] = config_dict(resolve_plugins(r.robot.model));
    } catch (const LoadError& e) {
      rd["config"] = py::none();
      rd["config_error"] = e.what();
    }
    robots.append(rd);
  }
  out["robots"] = robots;
  py::list diags;  // what the loader found (e.g. masses outside the stated range)
  for (const auto& x : d.diagnostics) diags.append(diagnostic(x));
  out["diagnostics"] = diags;
  return out;
}

// world_tool check (docs/COMPAT-validation.md "world_tool check"): one call that flattens, checks and loads.
void bind_world_check(py::module_& m) {
  m.def(
      "check_world",
      [](const std::string& path) {
        const WorldCheck c = check_world_file(path);
        py::dict out;
        py::list findings;
        for (const auto& d : c.findings) findings.append(diagnostic(d));
        out["findings"] = findings;
        out["world"] = c.world ? py::object(world_dict(*c.world)) : py::object(py::none());
        return out;
      },
      py::arg("path"),
      "A world file read as world_tool check reads it: flattened, held to the check's rules, then loaded. "
      "{findings: [{severity, code, element, message, line}], world: the loaded world as load_world_file returns "
      "it, or None when an error came first}. A bad world is findings, never an exception.");
}

}  // namespace

// ---- the bindings, one function per area, called in this order by PYBIND11_MODULE ---------------------------

namespace {

// URDF robots: loading, inspecting (car check), the plug-in schemas and the inertia rule.
void bind_urdf(py::module_& m) {
  m.def(
      "load_urdf_string",
      [](const std::string& xml, const std::string& source, bool throw_on_error) {
        LoadOptions o;
        o.throw_on_error = throw_on_error;
        return model_dict(load_urdf_string(xml, source, o));
      },
      py::arg("xml"), py::arg("source") = "<string>", py::arg("throw_on_error") = true,
      "Load a URDF document into the core's model; returns it as a dict. Raises LoadError.");
  m.def(
      "load_urdf_file",
      [](const std::string& path, bool throw_on_error) {
        LoadOptions o;
        o.throw_on_error = throw_on_error;
        return model_dict(load_urdf_file(path, o));
      },
      py::arg("path"), py::arg("throw_on_error") = true, "Load a URDF file; returns the model as a dict.");
  m.def(
      "inspect_urdf_string",
      [](const std::string& xml, const std::string& source, bool lump_fixed_joints) {
        LoadOptions o;
        o.throw_on_error = false;
        o.lump_fixed_joints = lump_fixed_joints;
        // an <sdf> document is read as an SDF robot (docs/COMPAT-sdf.md); SDF keeps fixed joints either way
        const RobotModel model = is_sdf_document(xml) ? load_sdf_model_string(xml, source, o).model
                                                      : load_urdf_string(xml, source, o);
        py::dict out;
        out["model"] = model_dict(model);
        // A plug-in that cannot be configured is reported as an error finding, not raised.
        try {
          out["config"] = config_dict(resolve_plugins(model));
          out["config_error"] = py::none();
        } catch (const LoadError& e) {
          out["config"] = py::none();
          out["config_error"] = error_finding("plugin-config", e);
        }
        // A collision mesh that cannot be found or read is the spawn's load error: an error finding here; a
        // visual's is the spawn's warning (mesh_warnings).
        out["mesh_error"] = py::none();
        py::list mesh_warnings;
        try {
          RobotModel with_meshes = model;
          const auto slash = source.rfind('/');
          load_meshes(&with_meshes, slash == std::string::npos ? "" : source.substr(0, slash));
          for (size_t i = model.diagnostics.size(); i < with_meshes.diagnostics.size(); ++i)
            mesh_warnings.append(diagnostic(with_meshes.diagnostics[i]));
        } catch (const LoadError& e) {
          out["mesh_error"] = error_finding("mesh-load", e);
        }
        out["mesh_warnings"] = mesh_warnings;
        return out;
      },
      py::arg("xml"), py::arg("source") = "<string>", py::arg("lump_fixed_joints") = true,
      "Load a URDF keeping every finding, and resolve its plug-ins: {model, config, config_error}.");
  m.def(
      "plugin_schema",
      [](const std::string& kind) {
        py::list l;
        for (const auto& d : plugin_schema(kind)) l.append(py::make_tuple(d.key, d.default_value, d.unit));
        return l;
      },
      py::arg("kind"), "Keys, defaults and units of a plug-in kind.");
  m.def("plugin_kind", &plugin_kind, py::arg("filename"));
  m.def(
      "inertial_problem",
      [](double mass, const std::vector<std::vector<double>>& inertia) {
        if (inertia.size() != 3) throw std::invalid_argument("inertia must be 3 x 3");
        Eigen::Matrix3d I;
        for (int r = 0; r < 3; ++r) {
          if (inertia[r].size() != 3) throw std::invalid_argument("inertia must be 3 x 3");
          for (int c = 0; c < 3; ++c) I(r, c) = inertia[r][c];
        }
        std::string code;
        const std::string why = inertial_problem(mass, I, &code);
        return py::make_tuple(code, why);
      },
      py::arg("mass"), py::arg("inertia"),
      "(code, reason) when the mass cannot be loaded (not > 0), ('', '') when it can.");
}

// model:// paths, the URI rule and the geometry car simulates.
void bind_paths(py::module_& m) {
  m.def("model_path", &car_sim::model_path, "Where model:// looks, in order.");
  m.def("resolve_uri", py::overload_cast<const std::string&, const std::string&>(&car_sim::resolve_uri),
        py::arg("uri"), py::arg("base_dir") = "", "The include rule: a path for a URI, '' when not found.");

  bind_world_check(m);
}

// SDF worlds: the flattener, the loaders and the parsed WorldDescription.
void bind_worlds(py::module_& m) {
  // The world flattener (world_tool) and its loader: LoadError with the error's parts as attributes file, element
  // and reason. With a list for warnings, an include that resolves nowhere is left out and its warning appended
  // there (as the simulator does); without, it is an error.
  auto flat = [m](const std::string& path, py::object warnings, auto read) {
    try {
      std::vector<Diagnostic> found;
      auto out = read(path, warnings.is_none() ? nullptr : &found);
      for (const auto& d : found) warnings.attr("append")(diagnostic(d));
      return out;
    } catch (const LoadError& e) {
      py::object type = m.attr("LoadError");
      py::object err = type(e.what());
      err.attr("file") = e.file();
      err.attr("element") = e.element();
      err.attr("reason") = e.reason();
      PyErr_SetObject(type.ptr(), err.ptr());
      throw py::error_already_set();
    }
  };
  m.def(
      "flatten_world",
      [flat](const std::string& path, py::object warnings) {
        // bytes: the text keeps the input's encoding, named in its declaration
        return flat(path, warnings, [](const std::string& p, std::vector<Diagnostic>* w) {
          return py::bytes(flatten_world_file(p, w));
        });
      },
      py::arg("path"), py::arg("warnings") = py::none(),
      "A world file as one self-contained SDF text (bytes, in the encoding its declaration names): includes expanded (the loader's include rule, at most 32 deep), "
      "nested models hoisted as 'parent::child', <state> applied. Raises LoadError (with file, element, reason).");

  m.def(
      "load_flattened_world",
      [flat](const std::string& path, py::object warnings) {
        return flat(path, warnings, [](const std::string& p, std::vector<Diagnostic>* w) {
          return world_dict(load_flattened_world(p, w));
        });
      },
      py::arg("path"), py::arg("warnings") = py::none(),
      "A world file flattened as flatten_world flattens it, then loaded, in one call: the dict load_world_file "
      "gives (world_tool map and plot). Raises LoadError (with file, element, reason).");
  m.def("load_world_file", [](const std::string& path) { return world_dict(load_world_file(path)); }, py::arg("path"),
        "An SDF world as the simulator reads it (sdformat, includes resolved, <state> applied), as a dict.");
  m.def(
      "load_world_string",
      [](const std::string& xml, const std::string& source) { return world_dict(load_world_string(xml, source)); },
      py::arg("xml"), py::arg("source") = "<string>", "load_world_file for SDF text.");

  // Parsed once, built many times: a world's const description and a robot's const model as opaque handles. A
  // World built from them copies what it keeps, so one handle serves every run of a worker (docs/BATCH.md).
  py::class_<WorldDescription, std::shared_ptr<WorldDescription>>(
      m, "WorldDescription", "A parsed SDF world (const): pass it to World() to build a world without parsing again.")
      .def_property_readonly("name", [](const WorldDescription& d) { return d.name; })
      .def_property_readonly("source", [](const WorldDescription& d) { return d.source; })
      .def_property_readonly("step_size", [](const WorldDescription& d) { return d.step_size; }, "[s]")
      .def("to_dict", &world_dict, "The description as load_world_file returns it.");
  m.def(
      "parse_world_file",
      [](const std::string& path) { return std::make_shared<WorldDescription>(load_world_file(path)); },
      py::arg("path"),
      "An SDF world parsed once (sdformat, includes resolved, <state> applied), as a WorldDescription.");
  m.def(
      "parse_world_string",
      [](const std::string& xml, const std::string& source) {
        return std::make_shared<WorldDescription>(load_world_string(xml, source));
      },
      py::arg("xml"), py::arg("source") = "<string>", "parse_world_file for SDF text.");
  m.def(
      "empty_world_description", [] { return std::make_shared<WorldDescription>(empty_world()); },
      "Gazebo's empty world (ground plane, sun) as a WorldDescription.");
}

// A parsed robot: the RobotModel handle.
void bind_robot_model(py::module_& m) {
  py::class_<RobotModel, std::shared_ptr<RobotModel>>(
      m, "RobotModel", "A parsed URDF robot (const): pass it to World.spawn_model to spawn it without parsing again.")
      .def_property_readonly("name", [](const RobotModel& r) { return r.name; })
      .def("to_dict", &model_dict, "The model as load_urdf_string returns it.");
  m.def(
      "parse_urdf_string",
      [](const std::string& xml, const std::string& source) {
        return std::make_shared<RobotModel>(load_urdf_string(xml, source));
      },
      py::arg("xml"), py::arg("source") = "<string>", "URDF text parsed once into a RobotModel. Raises LoadError.");
}

// World: building it, spawning and removing models, stepping, resetting, commanding.
void bind_world_run(py::class_<World>& world) {
  world
      .def(py::init([](const WorldDescription& desc, int solver_iterations, uint64_t seed) {
             WorldOptions o;
             o.solver_iterations = solver_iterations;
             o.seed = seed;
             return std::make_unique<World>(desc, o);  // a copy: the description stays as it was
           }),
           py::arg("description"), py::arg("solver_iterations") = 10, py::arg("seed") = 0,
           "Build a world from a parsed WorldDescription (parse_world_file), without parsing again.")
      .def(py::init([](const std::optional<std::string>& world_file, int solver_iterations, uint64_t seed) {
             WorldOptions o;
             o.solver_iterations = solver_iterations;
             o.seed = seed;
             return std::make_unique<World>(world_file ? load_world_file(*world_file) : empty_world(), o);
           }),
           py::arg("world_file") = py::none(), py::arg("solver_iterations") = 10, py::arg("seed") = 0,
           "Load an SDF world file, or Gazebo's empty world (ground plane, sun) when None.")
      .def_property_readonly("dt", &World::dt, "step size [s]")
      .def_property_readonly("tick", &World::tick, "steps taken since the start or the last reset")
      .def_property_readonly("time", &World::time, "simulated time [s] = tick * dt")
      .def(
          "spawn_urdf",
          [](World& w, const std::string& xml, const std::string& name, double x, double y, double z, double roll,
             double pitch, double yaw, const std::string& ns) {
            w.spawn(load_urdf_string(xml, name), name, pose_of(x, y, z, roll, pitch, yaw), ns);
          },
          py::arg("xml"), py::arg("name"), py::arg("x") = 0.0, py::arg("y") = 0.0, py::arg("z") = 0.0,
          py::arg("roll") = 0.0, py::arg("pitch") = 0.0, py::arg("yaw") = 0.0, py::arg("robot_namespace") = "",
          "Spawn a robot from URDF text with its root link at the given pose.")
      .def(
          "spawn_model",
          [](World& w, const RobotModel& model, const std::string& name, double x, double y, double z, double roll,
             double pitch, double yaw, const std::string& ns) {
            w.spawn(model, name, pose_of(x, y, z, roll, pitch, yaw), ns);
          },
          py::arg("model"), py::arg("name"), py::arg("x") = 0.0, py::arg("y") = 0.0, py::arg("z") = 0.0,
          py::arg("roll") = 0.0, py::arg("pitch") = 0.0, py::arg("yaw") = 0.0, py::arg("robot_namespace") = "",
          "spawn_urdf for a parsed RobotModel (parse_urdf_string): the world keeps its own copy.")
      .def(
          "spawn_sdf",
          [](World& w, const std::string& xml, const std::string& name, double x, double y, double z, double roll,
             double pitch, double yaw, const std::string& ns) {
            w.spawn_sdf(load_sdf_model_string(xml, name), name, pose_of(x, y, z, roll, pitch, yaw), ns);
          },
          py::arg("xml"), py::arg("name"), py::arg("x") = 0.0, py::arg("y") = 0.0, py::arg("z") = 0.0,
          py::arg("roll") = 0.0, py::arg("pitch") = 0.0, py::arg("yaw") = 0.0, py::arg("robot_namespace") = "",
          "Spawn a robot from SDF text (docs/COMPAT-sdf.md): the pose goes on top of the model's own <pose>.")
      .def("remove", &World::remove, py::arg("name"))
      .def("step", &World::step, py::arg("n") = 1, py::call_guard<py::gil_scoped_release>(),
           "Advance n fixed steps (releases the GIL).")
      .def("reset", &World::reset, "Time to zero, every model where it started (reset_simulation).")
      .def("reset_poses", &World::reset_poses, "Every model where it started, time goes on (reset_world).")
      .def("reset_time", &World::reset_time, "Time to zero, models and plug-ins as they are (Gazebo's ResetTime).")
      .def("set_cmd_vel", py::overload_cast<const std::string&, double, double>(&World::set_cmd_vel), py::arg("robot"),
           py::arg("v"), py::arg("w"), "Command the robot's drive plug-ins: v [m/s] forward, w [rad/s] about z.");
}

// World: model and link states, joints, contacts, plug-ins and what they measured.
void bind_world_read(py::class_<World>& world) {
  world
      .def("model_names", &World::model_names)
      .def("robot_names", &World::robot_names)
      .def("model_state", [](const World& w, const std::string& n) { return state_dict(w.model_state(n)); },
           py::arg("name"), "Pose and twist of a model's frame, world frame.")
      .def(
          "set_model_state",
          [](World& w, const std::string& n, std::vector<double> position, std::vector<double> orientation,
             std::vector<double> linear, std::vector<double> angular) {
            if (position.size() != 3 || orientation.size() != 4 || linear.size() != 3 || angular.size() != 3)
              throw std::invalid_argument("position, linear, angular need 3 values, orientation 4 (x y z w)");
            ModelState s;
            s.pose.translation() = Eigen::Vector3d(position[0], position[1], position[2]);
            s.pose.linear() = Eigen::Quaterniond(orientation[3], orientation[0], orientation[1], orientation[2])
                                  .normalized().toRotationMatrix();
            s.linear = Eigen::Vector3d(linear[0], linear[1], linear[2]);
            s.angular = Eigen::Vector3d(angular[0], angular[1], angular[2]);
            w.set_model_state(n, s);
          },
          py::arg("name"), py::arg("position"), py::arg("orientation") = std::vector<double>{0, 0, 0, 1},
          py::arg("linear") = std::vector<double>{0, 0, 0}, py::arg("angular") = std::vector<double>{0, 0, 0})
      .def(
          "joint_states",
          [](const World& w, const std::string& robot) {
            py::dict d;
            for (const auto& j : w.joint_states(robot)) d[py::str(j.name)] = py::make_tuple(j.position, j.velocity);
            return d;
          },
          py::arg("robot"), "{joint: (position, velocity)} for every non-fixed joint.")
      .def(
          "link_pose",
          [](const World& w, const std::string& robot, const std::string& link) {
            ModelState s;
            s.pose = w.link_pose(robot, link);
            py::dict d = state_dict(s);
            d.attr("pop")("linear");
            d.attr("pop")("angular");
            return d;
          },
          py::arg("robot"), py::arg("link"))
      .def(
          "contacts",
          [](const World& w) {
            py::list out;
            for (const auto& c : w.contacts()) {
              py::dict d;
              d["a"] = c.a;
              d["b"] = c.b;
              d["position"] = vec(c.position);
              d["normal_force"] = c.normal_force;
              out.append(d);
            }
            return out;
          },
          "Contacts of the last step with a positive normal force [N].")
      .def(
          "sensors",
          [](const World& w) {
            py::list out;
            for (const auto& s : w.sensors()) out.append(plugin_info_dict(s));
            return out;
          },
          "Every measuring plug-in (computed only while active) of every robot.")
      .def(
          "plugins",
          [](const World& w) {
            py::list out;
            for (const auto& s : w.plugins()) out.append(plugin_info_dict(s));
            return out;
          },
          "Every plug-in instance of every robot, in spawn order.")
      .def("set_sensor_active", &World::set_sensor_active, py::arg("robot"), py::arg("plugin"), py::arg("active") = true,
           "A sensor computes only while active.")
      .def(
          "take_sensor_outputs",
          [](World& w) {
            // one list per output group of the measuring kinds ("scans", "images", "imus", ...)
            py::dict out;
            std::map<std::pair<std::string, std::string>, std::string> group;
            for (const PluginKind* k : plugin_kinds())
              if (k->lazy && !k->output_group.empty() && !out.contains(k->output_group.c_str()))
                out[k->output_group.c_str()] = py::list();
            for (const auto& s : w.sensors()) group[{s.robot, s.config.name}] = s.kind->output_group;
            const OutputQueue taken = w.take_outputs_if([&](const Output& o) { return group.count({o.robot, o.plugin}) > 0; });
            for (const auto& o : taken) {
              const std::string& g = group.at({o->robot, o->plugin});
              if (!out.contains(g.c_str())) out[g.c_str()] = py::list();
              out[g.c_str()].cast<py::list>().append(output_dict(*o, w.dt()));
            }
            return out;
          },
          "Measurements since the last call, by group: {'scans', 'images', 'imus', ...}, arrays as NumPy.")
      .def(
          "take_odometry",
          [](World& w) {
            py::list out;
            for (const auto& o : w.take_odometry()) {
              py::dict d = output_dict(o, w.dt());
              d["model"] = o.robot;
              out.append(d);
            }
            return out;
          },
          "Odometry samples of the drive plug-ins since the last call (base twist in the base frame).");
}

// Colours, the plug-in kinds, and stepping many worlds at once.
void bind_tools(py::module_& m) {
  m.def(
      "gazebo_colours", [] { 
        py::dict d;
        for (const auto& [name, c] : gazebo_colours()) d[name.c_str()] = py::make_tuple(c[0], c[1], c[2], c[3]);
        return d;
      },
      "Gazebo's standard materials as RGBA (config/gazebo_materials.txt).");
  m.def(
      "visual_colour",
      [](const std::string& script, const std::optional<std::vector<double>>& diffuse,
         const std::optional<std::vector<double>>& ambient) {
        auto v4 = [](const std::optional<std::vector<double>>& v) -> std::optional<Eigen::Vector4d> {
          if (!v) return std::nullopt;
          if (v->size() != 4) throw std::invalid_argument("a colour needs 4 values (r g b a)");
          return Eigen::Vector4d((*v)[0], (*v)[1], (*v)[2], (*v)[3]);
        };
        const Eigen::Vector4d c = visual_colour(script, v4(diffuse), v4(ambient));
        return py::make_tuple(c[0], c[1], c[2], c[3]);
      },
      py::arg("script") = "", py::arg("diffuse") = py::none(), py::arg("ambient") = py::none(),
      "The colour rule for an SDF visual: a known Gazebo/Name script, else diffuse, else ambient, else grey.");
  m.def(
      "plugin_kinds",
      [] {
        py::list out;
        for (const PluginKind* k : plugin_kinds()) {
          py::dict d;
          d["name"] = k->name;
          d["filenames"] = k->filenames;
          d["sensor_types"] = k->sensor_types;
          d["model_level"] = k->model_level;
          d["lazy"] = k->lazy;
          out.append(d);
        }
        return out;
      },
      "Every plug-in kind of the registry: name, Gazebo file names, sensor types.");
  m.def(
      "link_colours",
      [](const std::string& xml, const std::string& base_dir) {
        RobotModel model = load_urdf_string(xml);
        load_meshes(&model, base_dir);
        py::dict out;
        for (const Link& l : model.links) {
          const Eigen::Vector4d c = link_colour(l);
          out[py::str(l.name)] = py::make_tuple(c[0], c[1], c[2], c[3]);
        }
        return out;
      },
      py::arg("xml"), py::arg("base_dir") = "",
      "The colour rule for each link of a URDF (its <gazebo><material>, else its URDF colour, else a visual mesh's\n"
      "own colour, else grey): {link: (r, g, b, a)}. Relative mesh URIs start at base_dir.");
  m.def(
      "step_worlds",
      [](const std::vector<World*>& worlds, int n) {
        // one call for a whole vector of worlds (car.gym's vector env): no Python between them, the GIL released
        py::gil_scoped_release release;
        step_worlds(worlds, static_cast<uint64_t>(n));
      },
      py::arg("worlds"), py::arg("n") = 1,
      "Advance each world n steps, the worlds on car's thread pool, without the GIL (docs/BATCH.md). ValueError "
      "when a world appears twice.");
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "car_sim core: URDF model loading and plug-in configuration (no ROS).";
  py::register_exception<LoadError>(m, "LoadError", PyExc_ValueError);
  // a body whose state turned non-finite stops the world: car._core.SimulationError (a RuntimeError)
  py::register_exception<SimulationError>(m, "SimulationError", PyExc_RuntimeError);
  bind_urdf(m);
  bind_paths(m);
  bind_worlds(m);
  bind_robot_model(m);
  py::class_<World> world(m, "World", "A simulated world, stepped in fixed ticks. No ROS master needed.");
  bind_world_run(world);
  bind_world_read(world);
  bind_tools(m);
}

// car._core: the pybind11 skin over the car_sim core. Models come back as plain dicts and lists;
// LoadError becomes car._core.LoadError (a ValueError) with the core's "file:line: element: reason" text.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "car_sim/model.hpp"
#include "car_sim/plugins.hpp"

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
    case ShapeType::Mesh: d["uri"] = s.mesh_uri; d["scale"] = vec(s.mesh_scale); break;
    case ShapeType::Plane: d["normal"] = vec(s.normal); break;
  }
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

py::dict model_dict(const RobotModel& m) {
  py::dict d;
  d["name"] = m.name;
  d["source"] = m.source;
  d["root_link"] = m.root_link;
  py::list links;
  for (const auto& l : m.links) {
    py::dict ld;
    ld["name"] = l.name;
    if (l.inertial) {
      py::dict in;
      in["mass"] = l.inertial->mass;
      in["origin"] = pose(l.inertial->origin);
      in["inertia"] = mat(l.inertial->inertia);
      ld["inertial"] = in;
    } else {
      ld["inertial"] = py::none();
    }
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

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "car_sim core: URDF model loading and plug-in configuration (no ROS).";
  py::register_exception<LoadError>(m, "LoadError", PyExc_ValueError);

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
      [](const std::string& xml, const std::string& source) {
        LoadOptions o;
        o.throw_on_error = false;
        const RobotModel model = load_urdf_string(xml, source, o);
        py::dict out;
        out["model"] = model_dict(model);
        // A plug-in that cannot be configured is reported as an error finding, not raised.
        try {
          out["config"] = config_dict(resolve_plugins(model));
          out["config_error"] = py::none();
        } catch (const LoadError& e) {
          out["config"] = py::none();
          py::dict err;
          err["severity"] = "error";
          err["code"] = "plugin-config";
          err["element"] = e.element();
          err["message"] = e.reason();
          err["line"] = e.line();
          out["config_error"] = err;
        }
        return out;
      },
      py::arg("xml"), py::arg("source") = "<string>",
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
}

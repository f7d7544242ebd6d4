// car's Gazebo 11 API: the world's pause flag and reset, model insertion (World::InsertModel*, and msgs::Factory on
// ~/factory through transport::Node and Publisher), each on car_sim::World's public calls (docs/PLUGINS.md
// "Inserting models"). Gazebo's rule (gazebo/physics/World.cc): InsertModel* queue a factory message, and
// World::ProcessFactoryMsgs loads it after a step's update; car inserts it at the end of the next step.
#include <sstream>
#include <stdexcept>

#include "car_sim/sdf_model.hpp"
#include "car_sim/world.hpp"
#include "gazebo/common/Console.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/World.hh"
#include "gazebo/transport/transport.hh"
#include "hub.hpp"

namespace car_gazebo {

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string pose_text(const ignition::math::Pose3d& p) {
  std::ostringstream os;
  os.precision(17);
  const auto e = p.Rot().Euler();
  os << p.Pos().X() << " " << p.Pos().Y() << " " << p.Pos().Z() << " " << e.X() << " " << e.Y() << " " << e.Z();
  return os.str();
}

// The model document of an insertion, as one SDF text car's SDF loader reads, with the pose put in; "" after a gzerr.
std::string model_document(const Hub::Insert& what) {
  if (!what.file.empty()) {
    // a file by car's include rule (model:// through the model path, the folder's model.config), as Gazebo's
    // ModelDatabase::GetModelFile; an include's <pose> replaces the model's, as the factory message's pose does
    return "<sdf version='1.6'><world name='factory'><include><uri>" + xml_escape(what.file) + "</uri>" +
           (what.pose ? "<pose>" + pose_text(*what.pose) + "</pose>" : std::string()) + "</include></world></sdf>";
  }
  sdf::SDFPtr doc(new sdf::SDF());
  sdf::init(doc);
  if (!sdf::readString(what.sdf, doc)) {
    gzerr << "Unable to read sdf string[" << what.sdf << "]\n";
    return "";
  }
  sdf::ElementPtr e = doc->Root();
  if (e->HasElement("world")) e = e->GetElement("world");
  if (!e->HasElement("model")) {
    gzerr << "Unable to find a model in:\n" << what.sdf << "\n(car inserts models only: no lights or actors)\n";
    return "";
  }
  sdf::ElementPtr model = e->GetElement("model");
  if (what.pose) model->GetElement("pose")->Set(*what.pose);
  return "<sdf version='" + doc->Root()->Get<std::string>("version") + "'>" + model->ToString("") + "</sdf>";
}

// Gazebo's ProcessFactoryMsgs for one model: the name unique (UniqueModelName: NAME_0, NAME_1, ...) unless renaming
// is off, then the model and its plug-ins.
void insert_now(car_sim::World& world, const Hub::Insert& what) {
  const std::string text = model_document(what);
  if (text.empty()) return;
  car_sim::SdfRobot robot;
  try {
    robot = car_sim::load_sdf_model_string(text, what.file.empty() ? "<inserted model>" : what.file);
  } catch (const std::exception& e) {
    gzerr << "Loading model from factory message failed: " << e.what() << "\n";
    return;
  }
  const std::string base = robot.model.name;
  if (base.empty()) {
    gzerr << "Can't load model with empty name\n";
    return;
  }
  std::string name = base;
  if (world.has_model(name)) {
    if (!what.allow_renaming) {
      gzwarn << "A model named [" << base << "] already exists and allow_renaming is false. Model won't be inserted.\n";
      return;
    }
    for (int i = 0; world.has_model(name); ++i) name = base + "_" + std::to_string(i);
  }
  try {
    world.spawn_sdf(robot, name, Eigen::Isometry3d::Identity());
  } catch (const std::exception& e) {
    gzerr << "Loading model from factory message failed: " << e.what() << "\n";
  }
}

}  // namespace

void Hub::insert(Insert what) {
  car_sim::World* w = core;
  core->defer([w, what = std::move(what)] { insert_now(*w, what); });
}

}  // namespace car_gazebo

namespace gazebo {

namespace msgs {

void Set(Pose* _p, const ignition::math::Pose3d& _v) { _p->value = _v; }
ignition::math::Pose3d ConvertIgn(const Pose& _p) { return _p.value; }

void Set(Time* _t, const common::Time& _v) {
  _t->set_sec(_v.sec);
  _t->set_nsec(_v.nsec);
}

Time Convert(const common::Time& _t) {
  Time t;
  Set(&t, _t);
  return t;
}

common::Time Convert(const Time& _t) { return common::Time(_t.sec(), _t.nsec()); }

}  // namespace msgs

namespace physics {

bool World::IsPaused() const { return world->paused(); }

void World::SetPaused(bool _p) { world->set_paused(_p); }

void World::Reset() {
  car_sim::World* w = world;
  car_gazebo::Hub* h = car_gazebo::Hub::named(Name());
  // inside an update event the step is not over: the reset comes at its end
  if (h && h->in_step)
    w->defer([w] { w->reset(); });
  else
    w->reset();
}

namespace {

car_gazebo::Hub& hub_named(const std::string& name) {
  car_gazebo::Hub* h = car_gazebo::Hub::named(name);
  if (!h) throw std::logic_error("no world named '" + name + "' has a plug-in running: nothing to insert the model into");
  return *h;
}

}  // namespace

void World::InsertModelFile(const std::string& _sdfFilename) {
  car_gazebo::Hub::Insert what;
  what.file = _sdfFilename;
  hub_named(Name()).insert(std::move(what));
}

void World::InsertModelString(const std::string& _sdfString) {
  car_gazebo::Hub::Insert what;
  what.sdf = _sdfString;
  hub_named(Name()).insert(std::move(what));
}

void World::InsertModelSDF(const sdf::SDF& _sdf) { InsertModelString(_sdf.ToString()); }

}  // namespace physics

namespace transport {

Node::Node() = default;
Node::~Node() = default;

bool Node::Init(const std::string& _space) {
  if (_space.empty()) {
    car_gazebo::Hub* h = car_gazebo::Hub::current();
    this->topicNamespace = h ? h->world->Name() : "default";
  } else {
    this->topicNamespace = _space;
  }
  return true;
}

std::string Node::GetTopicNamespace() const { return this->topicNamespace; }

std::string Node::DecodeTopicName(const std::string& _topic) {
  if (_topic.rfind("~/", 0) == 0) return "/gazebo/" + this->topicNamespace + "/" + _topic.substr(2);
  return _topic;
}

template <>
PublisherPtr Node::Advertise<msgs::Factory>(const std::string& _topic, unsigned int, double) {
  const std::string topic = this->DecodeTopicName(_topic);
  if (topic != "/gazebo/" + this->topicNamespace + "/factory")
    throw std::invalid_argument("transport::Node::Advertise<msgs::Factory>(\"" + _topic +
                                "\"): car's transport offers only ~/factory (" + "/gazebo/" + this->topicNamespace +
                                "/factory), the world's model factory");
  return PublisherPtr(new Publisher(topic, "gazebo.msgs.Factory", this->topicNamespace));
}

Publisher::Publisher(const std::string& _topic, const std::string& _msgType, const std::string& _world)
    : topic(_topic), msgType(_msgType), world(_world) {}
Publisher::~Publisher() = default;
std::string Publisher::GetTopic() const { return this->topic; }
std::string Publisher::GetMsgType() const { return this->msgType; }

template <>
void Publisher::Publish<msgs::Factory>(const msgs::Factory& _message, bool) {
  car_gazebo::Hub::Insert what;
  if (_message.has_sdf() && !_message.sdf().empty()) {
    what.sdf = _message.sdf();
  } else if (_message.has_sdf_filename() && !_message.sdf_filename().empty()) {
    what.file = _message.sdf_filename();
  } else {
    gzerr << "Unable to load sdf from factory message.No SDF or SDF filename specified.\n";
    return;
  }
  if (_message.has_pose()) what.pose = msgs::ConvertIgn(_message.pose());
  what.allow_renaming = _message.allow_renaming();
  physics::hub_named(this->world).insert(std::move(what));
}

}  // namespace transport
}  // namespace gazebo

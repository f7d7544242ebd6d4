// Test plug-in in the style of Gazebo's factory tutorial: a world plug-in that inserts three models in its Load, one
// by each door: World::InsertModelFile("model://box"), World::InsertModelSDF of a sphere it renames
// "unique_sphere" (at (1, 0, 0) by its <pose>), and a msgs::Factory for model://cylinder at (1, -2, 0) published on
// ~/factory through transport::Node.
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>
#include <ignition/math/Pose3.hh>

namespace gazebo {
class WorldFactory : public WorldPlugin {
 public:
  void Load(physics::WorldPtr _world, sdf::ElementPtr /*_sdf*/) override {
    _world->InsertModelFile("model://box");

    sdf::SDF sphere;
    sphere.SetFromString(
        "<sdf version='1.6'><model name='sphere'><pose>1 0 0 0 0 0</pose><link name='link'>"
        "<pose>0 0 0.5 0 0 0</pose><inertial><mass>1</mass></inertial>"
        "<collision name='c'><geometry><sphere><radius>0.5</radius></sphere></geometry></collision>"
        "</link></model></sdf>");
    sphere.Root()->GetElement("model")->GetAttribute("name")->SetFromString("unique_sphere");
    _world->InsertModelSDF(sphere);

    transport::NodePtr node(new transport::Node());
    node->Init(_world->Name());
    transport::PublisherPtr pub = node->Advertise<msgs::Factory>("~/factory");
    msgs::Factory msg;
    msg.set_sdf_filename("model://cylinder");
    msgs::Set(msg.mutable_pose(),
              ignition::math::Pose3d(ignition::math::Vector3d(1, -2, 0), ignition::math::Quaterniond(0, 0, 0)));
    pub->Publish(msg);
  }
};
GZ_REGISTER_WORLD_PLUGIN(WorldFactory)
}  // namespace gazebo

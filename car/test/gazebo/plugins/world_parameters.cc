// Test plug-in in the style of Gazebo's parameters tutorial: a world plug-in that prints each element's value of its
// <plugin>, depth first, indented two spaces a level.
#include <gazebo/gazebo.hh>

#include <iostream>
#include <string>

namespace gazebo {
class WorldParameters : public WorldPlugin {
 public:
  void Load(physics::WorldPtr /*_world*/, sdf::ElementPtr _sdf) override { Print("", _sdf); }

 private:
  void Print(std::string _indent, sdf::ElementPtr _e) {
    if (_e->GetValue()) std::cout << _indent << _e->GetName() << "=" << _e->GetValue()->GetAsString() << "\n";
    _indent += "  ";
    for (sdf::ElementPtr c = _e->GetFirstElement(); c; c = c->GetNextElement()) Print(_indent, c);
  }
};
GZ_REGISTER_WORLD_PLUGIN(WorldParameters)
}  // namespace gazebo

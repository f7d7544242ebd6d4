"""The service types the rostests call, imported in one place (so moving them to a gazebo_msgs package is one
edit here)."""
from car.msg import ModelState, ModelStates  # noqa: F401
from car.srv import DeleteModel, GetModelState, GetWorldProperties, SetModelState, SpawnModel  # noqa: F401

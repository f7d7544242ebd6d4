"""The service types the rostests call, imported in one place."""
from gazebo_msgs.msg import ModelState, ModelStates  # noqa: F401
from gazebo_msgs.srv import DeleteModel, GetModelState, GetWorldProperties, SetModelState, SpawnModel  # noqa: F401

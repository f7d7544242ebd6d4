from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

# car.testing is a pytest plug-in: an install (setup.py install / pip) announces it to pytest through the pytest11
# entry point. catkin's devel space makes no entry points; CMakeLists.txt writes the same one there. car.ros holds the
# ROS nodes' modules (pip's wheel, pyproject.toml, leaves it out).
setup(**generate_distutils_setup(packages=['car', 'car.ros', 'car.testing'], package_dir={'': 'python'},
                                 entry_points={'pytest11': ['car.testing = car.testing']}))

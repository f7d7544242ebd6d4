"""car.testing: test robot code against the car simulator, judged in sim time (docs/TESTING.md).

As a pytest plug-in (entry point `car.testing`, or `-p car.testing`, or `pytest_plugins = ['car.testing']`):
the `sim` fixture, options --car-seed / --car-scope / --car-use-master / --car-artifacts / --car-rtf and the
`car_sim` marker. Outside pytest: `car.testing.sim.Sim` and, for rostest nodes, `car.testing.rostest`.
"""
from car.testing.plugin import (_car_sim_module, pytest_addoption, pytest_configure, pytest_configure_node,  # noqa: F401,E501
                                pytest_report_header, pytest_runtest_makereport, pytest_unconfigure, sim)

"""Where car's own files are (urdf/, worlds/, config/, models/): the source package in a checkout or a devel
space, ``<prefix>/share/car`` once installed (``catkin_make install``, the .debs), ``car/data`` beside the module in
a wheel (pip). The same rule as the core's ``car_package_dir`` (docs/INSTALL.md "Where car finds its files")."""
import os

_HERE = os.path.dirname(os.path.abspath(__file__))


def package_dir() -> str:
    """car's package folder: the one holding package.xml, urdf/ and worlds/."""
    # source and devel space: python/car/ sits in the package folder
    source = os.path.dirname(os.path.dirname(_HERE))
    if os.path.isfile(os.path.join(source, 'package.xml')):
        return source
    # install space: <prefix>/lib/python3/dist-packages/car/ beside <prefix>/share/car/
    prefix = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(_HERE))))
    share = os.path.join(prefix, 'share', 'car')
    if os.path.isfile(os.path.join(share, 'package.xml')):
        return share
    # a wheel (pip install, pyproject.toml): <site-packages>/car/data/
    data = os.path.join(_HERE, 'data')
    if os.path.isfile(os.path.join(data, 'package.xml')):
        return data
    raise RuntimeError('car: cannot find its package folder (package.xml) near %s' % _HERE)

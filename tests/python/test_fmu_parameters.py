"""The FMUs' named parameters (docs/conventions.md, docs/fmi.md): `clearance_um` acts as the
same edit of the scene string would, wins over the scene string's own value, and a value
outside its declared range is refused naming the parameter, through fmpy on FMI 2 and FMI 3.

The physics: a 6205 at the ring level, the shaft held 10 µm down at 1750 rpm. 20 µm of
diametral clearance takes 10 µm of radial play away from that offset, so the force must
fall by far more than 1 N; and the parameter and the scene edit must give the same bits."""

import pytest
from fmpy.fmi1 import FMICallException

from conftest import VERSIONS

SCENE = 'bearing = "6205"\n[model]\nlevel = "ring"\n'


def edited(um):
    return SCENE.replace('bearing = "6205"',
                         f'bearing = {{ preset = "6205", clearance_um = {um!r} }}')


MOTION = {"input_rule": "hold", "shaft.y": -10e-6, "shaft.omega": 183.26}


def force_y(host, version, scene, **params):
    h = host(version)
    h.set("scene", scene)
    for name, value in params.items():
        h.set(name, value)
    h.init(start_values=MOTION)
    h.step(0.0, 1e-4)
    return h.get(["force.y"])[0]


@pytest.mark.parametrize("version", VERSIONS)
def test_clearance_um_acts_as_the_same_scene_edit(host, version):
    base = force_y(host, version, SCENE)
    by_scene = force_y(host, version, edited(20.0))
    by_param = force_y(host, version, SCENE, clearance_um=20.0)
    assert by_param == by_scene, (by_param, by_scene)
    assert abs(by_param - base) > 1.0, (base, by_param)
    # over a scene string that gives its own clearance, the parameter wins
    assert force_y(host, version, edited(5.0), clearance_um=20.0) == by_scene


@pytest.mark.parametrize("version", VERSIONS)
def test_a_clearance_outside_its_range_is_refused_naming_it(host, version):
    h = host(version)
    with pytest.raises(FMICallException):
        h.set("clearance_um", 2000.0)
    text = " ".join(m for _, m in h.logs)
    assert "clearance_um" in text and "[-1000, 1000]" in text, text

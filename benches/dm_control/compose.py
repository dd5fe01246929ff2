# Copied from ../shared/users/compose.py (the program a dm_control user writes for
# benches W8; tools/compare_perf.py runs it from a folder where tests/ is the repo's).
# A real composition as dm_control users write it: an arm with a hand at its wrist,
# two arms in an arena, ten free props, and 200 randomized variants exported with their
# mesh files. Files: tests/conformance/cases/real_02_jaco_arm_with_hand (the corpus).
import numpy as np
from dm_control import mjcf

CASE = 'tests/conformance/cases/real_02_jaco_arm_with_hand'


def make_arm():
    arm = mjcf.from_path(f'{CASE}/jaco_arm.xml')
    hand = mjcf.from_path(f'{CASE}/jaco_hand.xml')
    for i in range(1, 7):
        arm.actuator.add('motor', name=f'm{i}', joint=f'joint_{i}', gear=[10])
    arm.find('site', 'wristsite').attach(hand)
    return arm


arena = mjcf.RootElement(model='arena')
arena.worldbody.add('light', pos=[0, 0, 3], directional=True)
arena.worldbody.add('geom', name='floor', type='plane', size=[3, 3, .1])
left = arena.worldbody.add('site', name='left', pos=[-.6, 0, 0])
right = arena.worldbody.add('site', name='right', pos=[.6, 0, 0], euler=[0, 0, 3.14159])
left.attach(make_arm())
right.attach(make_arm())

rng = np.random.default_rng(1)
props = []
for i in range(10):
    body = arena.worldbody.add('body', name=f'prop_{i}', pos=[*rng.uniform(-1, 1, 2), .5])
    body.add('freejoint', name=f'prop_{i}')
    props.append(body.add('geom', name=f'prop_{i}', type='box', size=[.03] * 3, mass=.1))

ring = arena.find('geom', 'jaco_arm_1/ring_2')
for v in range(200):
    for geom in props:
        geom.parent.pos = [*rng.uniform(-1, 1, 2), .5]
        geom.rgba = [*rng.uniform(0, 1, 3), 1]
    ring.size = [rng.uniform(.03, .06), .011]
    mjcf.export_with_assets(arena, 'variants', f'variant_{v:03}.xml')

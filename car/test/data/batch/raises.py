"""Controllers for the batch tests."""


def boom(obs):
    raise RuntimeError('controller exploded at t=%.2f' % obs['time'])


def forward(obs):
    return 0.5, 0.0

import pytest

import washer


@pytest.fixture(scope="session")
def params():
    return washer.load_params()


@pytest.fixture(scope="session")
def model(params):
    return washer.Model(params)


@pytest.fixture(scope="session")
def distinct_params(params):
    """Every coefficient distinct and nonzero (catches swapped terms)."""
    return params.replace(C_p=0.13, C_ox=0.41, C_oz=0.27, C_a=87.0, Omega=7.3, tau0=0.37,
                          r_tx=0.011, r_ty=-0.007, J_tx=0.93, J_ty=0.81, J_tz=0.77)


def random_state(rng, z=0.39):
    q = rng.normal(0, 0.05, 6)
    q[2] += z
    return q, rng.normal(0, 0.5, 6)

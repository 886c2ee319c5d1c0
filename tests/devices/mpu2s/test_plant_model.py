"""The genset plant alone (runtime/devices/mpu2s/plant.py), in virtual
nanoseconds: the slip integrated in closed form whatever the step, the
motor-potentiometer set points, the breaker closing on the phase of the
instant its closing time runs out, tripping, refusing, locking to the bus
and sharing load by droop, and a dead-bus close energising the bus.

Expected values are physics worked out here: phi(t) = phi0 + 360 * the
integral of the slip, the lag's response to a ramp, droop P = df / (droop *
f_rated) * P_rated. The plant's rates and times are its defaults (0.5 Hz/s,
2 %/s, lags 0.5 s and 0.3 s, droop 4 %, trip limit 20 deg)."""

from __future__ import annotations

import math

import pytest

from softplc.runtime.devices.mpu2s.plant import Breaker, Busbar, Genset, GensetPlant, wrap_deg

S = 1_000_000_000
MS = 1_000_000


def at(seconds: float) -> int:
    return round(seconds * S)


def run(plant: GensetPlant, step_ms: int, until_s: float, schedule: dict | None = None) -> dict:
    """Advance in steps of step_ms, stopping also at every schedule time to
    set its contacts; return phi at every schedule time and at the end."""
    schedule = {at(t): v for t, v in (schedule or {}).items()}
    points = sorted(set(schedule) | {at(until_s)})
    seen = {}
    for point in points:
        while plant.t < point:
            plant.advance(min(point, plant.t + step_ms * MS))
        seen[point] = plant.phase_deg
        for name, value in schedule.get(point, {}).items():
            setattr(plant, name, value)
    return seen


# ---------------------------------------------------------------- the phase


def test_constant_slip_turns_the_phase_at_360_deg_per_hz_and_second():
    plant = GensetPlant(Genset(f_offset=0.3), Busbar(f=50.0), phase_deg=10.0)
    plant.advance(at(2.5))
    assert plant.phase_deg == pytest.approx(wrap_deg(10.0 + 360.0 * 0.3 * 2.5), abs=1e-9)  # -80 deg
    assert plant.phase_deg == pytest.approx(-80.0, abs=1e-9)


def test_negative_slip_lags_and_a_drifting_bus_integrates_exactly():
    plant = GensetPlant(Genset(f_offset=-0.2), Busbar(f=50.0, drift_hz_s=0.01), phase_deg=0.0)
    plant.advance(at(3.0))
    # f_gen - f_bus = -0.2 - 0.01 t: integral -0.6 - 0.045 Hz*s
    assert plant.phase_deg == pytest.approx(wrap_deg(360.0 * (-0.2 * 3.0 - 0.01 * 9.0 / 2.0)), abs=1e-9)
    assert plant.f_bus == pytest.approx(50.03)


SCENARIO = {
    0.25: {"raise_f": True},
    0.62: {"raise_f": False, "lower_u": True},
    1.0: {"lower_f": True},
    1.7: {"lower_f": False, "lower_u": False, "raise_f": True},
    2.9: {"raise_f": False},
    3.3: {"gcb_close": True},  # bus live: closes at 3.38 s onto whatever phi is
}


@pytest.mark.parametrize("step_ms", [10, 37])
def test_the_phase_does_not_depend_on_the_step(step_ms):
    def plant():
        return GensetPlant(
            Genset(f_offset=0.12, u_offset=-6.0),
            Busbar(f=50.0, drift_hz_s=0.004),
            Breaker(closing_time_ms=80, trip_limit_deg=180.0),
            phase_deg=-150.0,
        )

    fine, coarse = plant(), plant()
    a = run(fine, 1, 3.3, SCENARIO)
    b = run(coarse, step_ms, 3.3, SCENARIO)
    assert a.keys() == b.keys()
    for t in a:
        assert a[t] == pytest.approx(b[t], abs=1e-6), t
    assert fine.f_gen == pytest.approx(coarse.f_gen, abs=1e-9)
    assert fine.u_gen == pytest.approx(coarse.u_gen, abs=1e-9)
    for p in (fine, coarse):  # on to the close at 3.38 s
        while p.t < at(3.5):
            p.advance(p.t + step_ms * MS if p is coarse else p.t + MS)
    assert fine.closes[0].t_ns == coarse.closes[0].t_ns == at(3.38)
    assert fine.closes[0].phase_deg == pytest.approx(coarse.closes[0].phase_deg, abs=1e-6)


def test_a_raise_pulse_turns_the_phase_as_the_lag_of_a_ramp():
    """Steady at slip 0, raise for tau = 0.4 s from t = 0, look at t1 = 1.5 s.
    The set point ramps r t then holds r tau; T x' = s - x gives
    x(t) = r (t - T (1 - e^(-t/T))) during the ramp, then relaxes to r tau."""
    r, lag, tau, t1 = 0.5, 0.5, 0.4, 1.5
    plant = GensetPlant(Genset(), Busbar(f=50.0), phase_deg=0.0)
    plant.raise_f = True
    plant.advance(at(tau))
    plant.raise_f = False
    plant.advance(at(t1))
    during = r * (tau * tau / 2 - lag * tau + lag * lag * (1 - math.exp(-tau / lag)))
    x_tau = r * (tau - lag * (1 - math.exp(-tau / lag)))
    after = r * tau * (t1 - tau) - (r * tau - x_tau) * lag * (1 - math.exp(-(t1 - tau) / lag))
    assert plant.phase_deg == pytest.approx(360.0 * (during + after), abs=1e-9)
    assert plant.f_gen == pytest.approx(50.0 + r * tau - (r * tau - x_tau) * math.exp(-(t1 - tau) / lag), abs=1e-12)


# ---------------------------------------------------------------- governor and AVR


def test_raise_and_lower_move_the_set_points_by_rate_times_time():
    plant = GensetPlant(Genset(), Busbar())
    g = plant.genset
    plant.raise_f = True
    plant.advance(at(0.3))  # 0.5 Hz/s * 0.3 s
    plant.raise_f = False
    plant.advance(at(1.0))
    plant.raise_f = True
    plant.advance(at(1.1))  # + 0.05
    plant.raise_f = False
    assert g.f.setpoint == pytest.approx(50.2)
    plant.lower_u = True
    plant.advance(at(1.6))  # 2 % of 400 V per s * 0.5 s = 4 V
    plant.lower_u = False
    assert g.u.setpoint == pytest.approx(396.0)
    plant.raise_u = plant.lower_u = True  # both: held
    plant.advance(at(2.0))
    assert g.u.setpoint == pytest.approx(396.0)
    plant.raise_u = plant.lower_u = False
    plant.advance(at(12.0))  # 20 lags: the values are at their set points
    assert plant.f_gen == pytest.approx(50.2, abs=1e-6)
    assert plant.u_gen == pytest.approx(396.0, abs=1e-6)


def test_first_order_lags():
    plant = GensetPlant(Genset(), Busbar())
    plant.raise_u = True
    plant.advance(at(0.3))  # U set point ramps 8 V/s for one lag
    # x(t) = r (t - T (1 - e^(-t/T))) with t = T: r T / e
    assert plant.u_gen - 400.0 == pytest.approx(8.0 * 0.3 / math.e, rel=1e-12)


def test_the_set_points_stay_within_ten_percent_of_rated():
    plant = GensetPlant(Genset(), Busbar())
    plant.raise_f = plant.lower_u = True
    plant.advance(at(30.0))
    assert plant.genset.f.setpoint == pytest.approx(55.0)
    assert plant.genset.u.setpoint == pytest.approx(360.0)


def test_start_ramps_a_stopped_engine_to_its_initial_set_points():
    plant = GensetPlant(Genset(running=False, f_offset=0.3, u_offset=-4.0), Busbar())
    plant.advance(at(1.0))
    assert plant.f_gen == 0.0 and not plant.gen_live
    plant.genset.start()
    plant.advance(at(3.5))  # half of the 5 s ramp
    assert plant.genset.f.setpoint == pytest.approx(25.15)
    plant.advance(at(20.0))
    assert plant.genset.f.setpoint == pytest.approx(50.3)
    assert plant.f_gen == pytest.approx(50.3, abs=1e-6)
    assert plant.u_gen == pytest.approx(396.0, abs=1e-6)
    assert plant.gen_live
    plant.genset.stop()
    plant.advance(at(30.0))
    assert plant.f_gen < 1e-4 and not plant.gen_live


def test_time_runs_forward():
    plant = GensetPlant()
    plant.advance(at(1.0))
    with pytest.raises(ValueError):
        plant.advance(at(0.5))


# ---------------------------------------------------------------- the breaker


def slipping(slip=0.2, phi0=0.0, **breaker) -> GensetPlant:
    return GensetPlant(Genset(f_offset=slip, u_offset=3.0), Busbar(f=50.0, u=400.0), Breaker(**breaker), phase_deg=phi0)


def test_the_breaker_closes_after_exactly_its_closing_time_on_that_instants_phase():
    # slip 0.2 Hz: 72 deg/s; commanded at 1.0 s, contacts at 1.08 s where phi = phi0 + 77.76
    plant = slipping(0.2, phi0=5.0 - 72.0 * 1.08, closing_time_ms=80)
    plant.advance(at(1.0))
    plant.gcb_close = True
    plant.advance(at(1.02))
    plant.gcb_close = False  # a 20 ms pulse: the close goes on
    plant.advance(at(1.08) - 1)
    assert not plant.gcb_closed and plant.closes == []
    plant.advance(at(1.08))
    assert plant.gcb_closed
    (close,) = plant.closes
    assert close.t_ns == at(1.08)
    assert close.phase_deg == pytest.approx(5.0, abs=1e-9)
    assert close.slip_hz == pytest.approx(0.2)
    assert close.voltage_diff == pytest.approx(3.0)
    assert not close.tripped and not close.dead_bus and plant.trips == 0


@pytest.mark.parametrize("closing_ms", [40, 150, 300])
def test_the_close_lands_inside_an_advance_step(closing_ms):
    plant = slipping(-0.3, phi0=0.0, closing_time_ms=closing_ms, trip_limit_deg=180.0)
    plant.gcb_close = True
    plant.advance(at(1.0))  # one big step over the close
    assert plant.closes[0].t_ns == closing_ms * MS
    assert plant.closes[0].phase_deg == pytest.approx(-360.0 * 0.3 * closing_ms / 1000.0, abs=1e-9)


def test_a_close_above_the_trip_limit_trips_and_is_counted():
    plant = slipping(0.2, phi0=25.0 - 72.0 * 0.08)  # contacts touch at +25 deg
    plant.gcb_close = True
    plant.advance(at(0.5))
    assert not plant.gcb_closed and plant.trips == 1
    assert plant.closes[0].tripped and plant.closes[0].phase_deg == pytest.approx(25.0)
    plant.advance(at(5.0))  # the close contact still held: no second close (no edge)
    assert len(plant.closes) == 1
    plant.gcb_close = False
    plant.advance(at(5.01))
    # phi(t) = 19.24 + 72 t: the contacts touch at 5.09 s on 385.72 = +25.72 deg: trips again
    plant.gcb_close = True
    plant.advance(at(6.0))
    assert plant.closes[1].phase_deg == pytest.approx(wrap_deg(25.0 + 72.0 * 5.01), abs=1e-9)
    assert plant.trips == 2


def test_a_breaker_that_refuses_never_closes():
    plant = slipping(0.0, refuse_close=True)
    for k in range(5):
        plant.gcb_close = True
        plant.advance(at(k + 0.2))
        plant.gcb_close = False
        plant.advance(at(k + 1.0))
    assert not plant.gcb_closed and plant.closes == [] and plant.breaker.refused == 5


def test_locked_to_the_bus_the_governor_moves_the_load_by_droop():
    plant = slipping(0.2, phi0=-72.0 * 0.08, closing_time_ms=80)
    plant.gcb_close = True
    plant.advance(at(0.1))
    plant.gcb_close = False
    plant.bus.drift_hz_s = 0.02
    assert plant.gcb_closed and plant.closes[0].phase_deg == pytest.approx(0.0, abs=1e-9)
    # droop 4 % of 50 Hz = 2 Hz for the rated 500 kW
    assert plant.p_kw == pytest.approx((50.2 - plant.f_bus) / 2.0 * 500.0)
    plant.raise_f = True
    plant.advance(at(1.1))  # + 0.5 Hz
    plant.raise_f = False
    plant.advance(at(2.0))
    assert plant.f_bus == pytest.approx(50.0 + 0.02 * 1.9)
    assert plant.f_gen == plant.f_bus and plant.phase_deg == 0.0 and plant.u_gen == plant.u_bus
    assert plant.p_kw == pytest.approx((50.7 - 50.038) / 2.0 * 500.0)
    # open (energise to open, 50 ms): unlocked, the engine runs back to its set point
    plant.gcb_open = True
    plant.advance(at(2.05) - 1)
    assert plant.gcb_closed
    plant.advance(at(2.05))
    assert not plant.gcb_closed and plant.p_kw == 0.0
    plant.gcb_open = False
    plant.advance(at(12.0))
    assert plant.f_gen == pytest.approx(50.7, abs=1e-6)


def test_open_relay_polarity_and_a_held_close():
    # de-energise to open (Ruhestrom): an undervoltage release that also blocks closing
    plant = slipping(0.0, open_energise=False)
    plant.gcb_close = True
    plant.advance(at(0.5))
    assert not plant.gcb_closed  # open contact off = open command
    plant.gcb_close, plant.gcb_open = False, True
    plant.advance(at(0.6))
    plant.gcb_close = True
    plant.advance(at(1.0))
    assert plant.gcb_closed
    plant.gcb_open = False  # de-energised: opens
    plant.advance(at(1.1))
    assert not plant.gcb_closed
    # Konstant: the close contact held keeps it closed, dropping it opens
    plant = slipping(0.0, constant_close=True)
    plant.gcb_close = True
    plant.advance(at(1.0))
    assert plant.gcb_closed
    plant.gcb_close = False
    plant.advance(at(1.0) + 50 * MS)
    assert not plant.gcb_closed


def test_a_dead_bus_close_energises_the_bus():
    plant = GensetPlant(Genset(f_offset=0.3, u_offset=-4.0), Busbar(live=False), Breaker(closing_time_ms=150))
    assert not plant.bus_live and plant.f_bus == 0.0 and plant.u_bus == 0.0
    plant.gcb_close = True
    plant.advance(at(0.1))
    plant.gcb_close = False
    plant.advance(at(0.2))
    assert plant.gcb_closed and plant.bus_live
    (close,) = plant.closes
    assert close.dead_bus and not close.tripped and close.t_ns == at(0.15)
    assert plant.f_bus == pytest.approx(50.3) and plant.u_bus == pytest.approx(396.0)
    plant.raise_f = True  # the island follows the genset
    plant.advance(at(1.2))
    plant.raise_f = False
    plant.advance(at(10.0))
    assert plant.f_bus == pytest.approx(50.8, abs=1e-6) and plant.f_gen == plant.f_bus
    assert plant.p_kw == 0.0
    with pytest.raises(ValueError):
        plant.bus.go_live(50.0, 400.0)
    plant.gcb_open = True
    plant.advance(at(10.1))
    assert not plant.gcb_closed and not plant.bus_live and plant.f_bus == 0.0


def test_a_dead_bus_going_live_later_starts_the_phase_from_where_it_stood():
    plant = GensetPlant(Genset(f_offset=0.1), Busbar(live=False), phase_deg=-90.0)
    plant.advance(at(1.0))
    assert plant.phase_deg == -90.0  # frozen: no bus to compare with
    plant.bus.go_live(50.0, 400.0)
    plant.advance(at(2.0))
    assert plant.phase_deg == pytest.approx(-90.0 + 36.0)

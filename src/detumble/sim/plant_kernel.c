/* Compiled plant kernel: the RK4 steps of RigidBody.step_env and wheels.step_with_wheels, and the circular-
 * orbit environment of Plant._update_environment (with the centred dipole, the orbit-constant field, or a field
 * tabulated along the orbit whose nodes Python computes: IGRF-14, the WMM), and the electrical and thermal
 * step (power.ElectricalSystem.step, thermal.ThermalModel.step), and the resolve of a held magnetometer or gyro
 * sample (sensors.Magnetometer._held_gauss, sensors.Gyro._held_rad_s: interpolation, bias, the noise drawn from
 * the sensor's random.Random as its gauss() draws it, quantisation), as a CPython extension module
 * (detumble.sim._plant_kernel).
 *
 * The pure-Python code in attitude.py, wheels.py, orbit.py, field.py, frames.py, power.py, sun.py (in_umbra),
 * thermal.py and control/quaternion.py
 * (rotate_n_to_b) is the reference. Every expression below is the reference's, operand for operand and in
 * the same order, so that with IEEE double arithmetic, no contraction into fused multiply-adds
 * (-ffp-contract=off) and the same libm sin/cos/sqrt/pow the interpreter's math module and float ** call,
 * the results are the same floats, bit for bit. detumble.sim.plant_kernel checks that when it loads this
 * module (and refuses it otherwise); tests/detumble/sim/test_plant_kernel.py checks whole trajectories.
 *
 * Units and frames as in the Python: state (q0..q3 scalar first = q_BN, omega_BN_B rad/s), m_B A m^2,
 * b_N tesla, r_hat_N unit, gg 1/s^2, t seconds since the scenario epoch, r_N metres; wheel momenta h
 * (absolute, along each spin axis) N m s, motor torques u N m.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <structmember.h>
#include <math.h>
#include <string.h>

#ifndef FL_SOURCE_KEY
#define FL_SOURCE_KEY "unknown"
#endif

/* --- numerics (no Python objects) ------------------------------------------------------------- */

typedef struct {
    double j[9], ji[9], h[3];          /* inertia, its inverse (row major, kg m^2), constant wheel momentum N m s */
} fl_body;

enum { FL_FIELD_DIPOLE = 1, FL_FIELD_ORBIT_CONSTANT = 2, FL_FIELD_TABLE = 3 };

typedef struct {
    int field;                                        /* FL_FIELD_DIPOLE, _ORBIT_CONSTANT or _TABLE */
    double a, u0, u_rate, raan0, raan_rate, ci, si;   /* CircularOrbit */
    double theta0, earth_rate, dx, dy, dz;            /* DipoleField (dipole vector in T m^3) */
    double b_O[3];                                    /* OrbitConstantField (tesla, orbit frame O) */
    /* FieldAlongOrbit with a table step: the step (s), the Python callable node(k) -> b_N at k * step
     * (FieldAlongOrbit._node: the model at the orbit's position then), and the two nodes last used */
    double table_step;
    PyObject *node_fn;
    long long k_lo, k_hi;
    double b_lo[3], b_hi[3];
    int nodes_held;                                   /* 0: none, 1: k_lo and k_hi hold */
} fl_env;

/* At most this many reaction wheels (a spacecraft has 3 or 4; the Python plant takes any number, and a
 * plant with more keeps it). */
#define FL_MAX_WHEELS 16

typedef struct {
    int n;                                            /* number of wheels */
    int friction;                                     /* WheelAssembly.friction */
    double g[3 * FL_MAX_WHEELS];                      /* spin axes in B, flat g1x g1y g1z g2x ... */
    double js[FL_MAX_WHEELS];                         /* axial inertia, kg m^2 */
    double cv[FL_MAX_WHEELS];                         /* viscous friction, N m s/rad */
    double cc[FL_MAX_WHEELS];                         /* Coulomb friction, N m */
    double sm[FL_MAX_WHEELS];                         /* Coulomb smoothing speed, rad/s */
} fl_wheels;

/* CircularOrbit.position_N(t), the unit vector Plant._update_environment derives from it, and the field
 * at that position: DipoleField.b_N(t, r_N), or OrbitConstantField.b_N(t, r_N) (which needs
 * CircularOrbit.velocity_N(t) and frames.orbit_axes_N). out = r_N[3], r_hat_N[3], b_N[3]. */
static int fl_table_field(fl_env *e, double t, double *b);

static int fl_environment(fl_env *e, double t, double *out)
{
    const double u = e->u0 + e->u_rate * t;
    const double raan = e->raan0 + e->raan_rate * t;
    const double cu = cos(u), su = sin(u);
    const double co = cos(raan), so = sin(raan);
    const double a = e->a;
    const double x = a * (co * cu - so * su * e->ci);
    const double y = a * (so * cu + co * su * e->ci);
    const double z = a * (su * e->si);
    const double rn = sqrt(x * x + y * y + z * z);
    out[0] = x;
    out[1] = y;
    out[2] = z;
    out[3] = x / rn;
    out[4] = y / rn;
    out[5] = z / rn;
    if (e->field == FL_FIELD_DIPOLE) {
        const double th = e->theta0 + e->earth_rate * t;
        const double c = cos(th), s = sin(th);
        const double dx = c * e->dx - s * e->dy;
        const double dy = s * e->dx + c * e->dy;
        const double dz = e->dz;
        const double r2 = x * x + y * y + z * z;
        const double r = sqrt(r2);
        const double inv_r3 = 1.0 / (r2 * r);
        const double k = 3.0 * (dx * x + dy * y + dz * z) / r2;
        out[6] = (k * x - dx) * inv_r3;
        out[7] = (k * y - dy) * inv_r3;
        out[8] = (k * z - dz) * inv_r3;
        return 0;
    }
    if (e->field == FL_FIELD_TABLE)
        return fl_table_field(e, t, out + 6);
    /* CircularOrbit.velocity_N (the same u and raan, so the same cosines and sines) */
    const double du = e->u_rate, dr = e->raan_rate, ci = e->ci;
    const double v0 = a * (du * (-co * su - so * cu * ci) + dr * (-so * cu - co * su * ci));
    const double v1 = a * (du * (-so * su + co * cu * ci) + dr * (co * cu - so * su * ci));
    const double v2 = a * du * cu * e->si;
    /* frames.orbit_axes_N: its squares are `** 2`, i.e. libm pow (this file is built -fno-builtin-pow) */
    const double on = sqrt(pow(x, 2.0) + pow(y, 2.0) + pow(z, 2.0));
    const double z0 = -x / on, z1 = -y / on, z2 = -z / on;
    const double hx = y * v2 - z * v1;
    const double hy = z * v0 - x * v2;
    const double hz = x * v1 - y * v0;
    const double hn = sqrt(hx * hx + hy * hy + hz * hz);
    const double y0 = -hx / hn, y1 = -hy / hn, y2 = -hz / hn;
    const double x0 = y1 * z2 - y2 * z1, x1 = y2 * z0 - y0 * z2, x2 = y0 * z1 - y1 * z0;
    const double ba = e->b_O[0], bb = e->b_O[1], bc = e->b_O[2];
    out[6] = ba * x0 + bb * y0 + bc * z0;
    out[7] = ba * x1 + bb * y1 + bc * z1;
    out[8] = ba * x2 + bb * y2 + bc * z2;
    return 0;
}

/* One node of the table from Python: b_N (T) at k * table_step. -1 with a Python error set. */
static int fl_table_node(fl_env *e, long long k, double *b)
{
    PyObject *res = PyObject_CallFunction(e->node_fn, "L", k);
    if (res == NULL)
        return -1;
    int bad = !PyTuple_Check(res) || PyTuple_GET_SIZE(res) != 3;
    for (Py_ssize_t i = 0; !bad && i < 3; i++) {
        b[i] = PyFloat_AsDouble(PyTuple_GET_ITEM(res, i));
        bad = b[i] == -1.0 && PyErr_Occurred();
    }
    Py_DECREF(res);
    if (bad && !PyErr_Occurred())
        PyErr_SetString(PyExc_TypeError, "a field table node must be a tuple of 3 floats");
    return bad ? -1 : 0;
}

/* FieldAlongOrbit.b_N(t) with a table step: nodes k = floor(t / step) and k + 1, linearly interpolated with
 * s = t / step - k (the same expressions; node k + 1 of one step is node k of the next, so Python is called
 * once per node). */
static int fl_table_field(fl_env *e, double t, double *b)
{
    const double h = e->table_step;
    const double kf = floor(t / h);
    const double s = t / h - kf;
    const long long k = (long long)kf;
    if (!e->nodes_held || e->k_lo != k) {
        if (e->nodes_held && e->k_hi == k) {
            memcpy(e->b_lo, e->b_hi, sizeof e->b_lo);
        } else {
            e->nodes_held = 0;
            if (fl_table_node(e, k, e->b_lo))
                return -1;
        }
        e->nodes_held = 0;
        if (fl_table_node(e, k + 1, e->b_hi))
            return -1;
        e->k_lo = k;
        e->k_hi = k + 1;
        e->nodes_held = 1;
    }
    const double *a = e->b_lo, *c = e->b_hi;
    b[0] = a[0] + s * (c[0] - a[0]);
    b[1] = a[1] + s * (c[1] - a[1]);
    b[2] = a[2] + s * (c[2] - a[2]);
    return 0;
}

/* --- the RK4 step: RigidBody.step_env and wheels.step_with_wheels ------------------------------------ */

/* The stage derivative of both (step_env written out, step_with_wheels' inner f): x = q0..q3, w1..w3,
 * b_B[3], r_hat_B[3]; hw the wheel momentum in B (N m s), t a torque on the body (N m); out = dx/dt. */
static void fl_stage_deriv(const fl_body *bd, const double *x, double hwx, double hwy, double hwz,
                           double tx, double ty, double tz, const double *m_B, double g, double *out)
{
    const double j11 = bd->j[0], j12 = bd->j[1], j13 = bd->j[2];
    const double j21 = bd->j[3], j22 = bd->j[4], j23 = bd->j[5];
    const double j31 = bd->j[6], j32 = bd->j[7], j33 = bd->j[8];
    const double i11 = bd->ji[0], i12 = bd->ji[1], i13 = bd->ji[2];
    const double i21 = bd->ji[3], i22 = bd->ji[4], i23 = bd->ji[5];
    const double i31 = bd->ji[6], i32 = bd->ji[7], i33 = bd->ji[8];
    const double mx = m_B[0], my = m_B[1], mz = m_B[2];
    const double q0 = x[0], q1 = x[1], q2 = x[2], q3 = x[3], w1 = x[4], w2 = x[5], w3 = x[6];
    const double b1 = x[7], b2 = x[8], b3 = x[9], r1 = x[10], r2 = x[11], r3 = x[12];
    const double s1 = j11 * r1 + j12 * r2 + j13 * r3;
    const double s2 = j21 * r1 + j22 * r2 + j23 * r3;
    const double s3 = j31 * r1 + j32 * r2 + j33 * r3;
    const double h1 = j11 * w1 + j12 * w2 + j13 * w3 + hwx;
    const double h2 = j21 * w1 + j22 * w2 + j23 * w3 + hwy;
    const double h3 = j31 * w1 + j32 * w2 + j33 * w3 + hwz;
    const double g1 = tx + my * b3 - mz * b2 + g * (r2 * s3 - r3 * s2) - (w2 * h3 - w3 * h2);
    const double g2 = ty + mz * b1 - mx * b3 + g * (r3 * s1 - r1 * s3) - (w3 * h1 - w1 * h3);
    const double g3 = tz + mx * b2 - my * b1 + g * (r1 * s2 - r2 * s1) - (w1 * h2 - w2 * h1);
    out[0] = 0.5 * (-q1 * w1 - q2 * w2 - q3 * w3);
    out[1] = 0.5 * (q0 * w1 + q2 * w3 - q3 * w2);
    out[2] = 0.5 * (q0 * w2 - q1 * w3 + q3 * w1);
    out[3] = 0.5 * (q0 * w3 + q1 * w2 - q2 * w1);
    out[4] = i11 * g1 + i12 * g2 + i13 * g3;
    out[5] = i21 * g1 + i22 * g2 + i23 * g3;
    out[6] = i31 * g1 + i32 * g2 + i33 * g3;
    out[7] = b2 * w3 - b3 * w2;
    out[8] = b3 * w1 - b1 * w3;
    out[9] = b1 * w2 - b2 * w1;
    out[10] = r2 * w3 - r3 * w2;
    out[11] = r3 * w1 - r1 * w3;
    out[12] = r1 * w2 - r2 * w1;
}

/* The RK4 stages with the body torque t held and the wheel momentum hw[s] at stage s: stage s is taken at
 * x0 + step * k[s - 1], step = dt / 2, dt / 2, dt (the reference's xa lists). */
static void fl_rk4_stages(const fl_body *bd, const double *x0, double dt, const double hw[4][3], const double *t,
                          const double *m_B, double g, double k[4][13])
{
    const double step[4] = {0.0, 0.5 * dt, 0.5 * dt, dt};
    double xa[13];
    fl_stage_deriv(bd, x0, hw[0][0], hw[0][1], hw[0][2], t[0], t[1], t[2], m_B, g, k[0]);
    for (int s = 1; s < 4; s++) {
        for (int j = 0; j < 13; j++)
            xa[j] = x0[j] + step[s] * k[s - 1][j];
        fl_stage_deriv(bd, xa, hw[s][0], hw[s][1], hw[s][2], t[0], t[1], t[2], m_B, g, k[s]);
    }
}

/* The RK4 combination of the body states and the renormalised quaternion: out[7]. */
static void fl_rk4_combine(const double *x0, const double k[4][13], double dt, double *out)
{
    const double c = dt / 6.0;
    double p[7];
    for (int j = 0; j < 7; j++)
        p[j] = x0[j] + c * (k[0][j] + 2.0 * (k[1][j] + k[2][j]) + k[3][j]);
    const double n = 1.0 / sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
    out[0] = p[0] * n;
    out[1] = p[1] * n;
    out[2] = p[2] * n;
    out[3] = p[3] * n;
    out[4] = p[4];
    out[5] = p[5];
    out[6] = p[6];
}

/* RigidBody.step_env with torque_B = tau: b_N and r_hat_N turned into B through the direction-cosine
 * matrix (step_env's own, not rotate_n_to_b), the body's constant wheel momentum at every stage. */
static void fl_step_env(const fl_body *bd, const double *st, double dt, const double *m_B, const double *b_N,
                        double g, const double *r_hat_N, const double *tau, double *out)
{
    const double q0 = st[0], q1 = st[1], q2 = st[2], q3 = st[3];
    const double c11 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3;
    const double c12 = 2.0 * (q1 * q2 + q0 * q3);
    const double c13 = 2.0 * (q1 * q3 - q0 * q2);
    const double c21 = 2.0 * (q1 * q2 - q0 * q3);
    const double c22 = q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3;
    const double c23 = 2.0 * (q2 * q3 + q0 * q1);
    const double c31 = 2.0 * (q1 * q3 + q0 * q2);
    const double c32 = 2.0 * (q2 * q3 - q0 * q1);
    const double c33 = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3;
    double x0[13], k[4][13], hw[4][3];
    for (int j = 0; j < 7; j++)
        x0[j] = st[j];
    x0[7] = c11 * b_N[0] + c12 * b_N[1] + c13 * b_N[2];
    x0[8] = c21 * b_N[0] + c22 * b_N[1] + c23 * b_N[2];
    x0[9] = c31 * b_N[0] + c32 * b_N[1] + c33 * b_N[2];
    x0[10] = c11 * r_hat_N[0] + c12 * r_hat_N[1] + c13 * r_hat_N[2];
    x0[11] = c21 * r_hat_N[0] + c22 * r_hat_N[1] + c23 * r_hat_N[2];
    x0[12] = c31 * r_hat_N[0] + c32 * r_hat_N[1] + c33 * r_hat_N[2];
    for (int s = 0; s < 4; s++)
        for (int i = 0; i < 3; i++)
            hw[s][i] = bd->h[i];
    fl_rk4_stages(bd, x0, dt, (const double (*)[3])hw, tau, m_B, g, k);
    fl_rk4_combine(x0, (const double (*)[13])k, dt, out);
}

/* wheels._friction: the bearing friction torque on wheel i at relative speed w (rad/s), N m. */
static double fl_friction(const fl_wheels *wh, int i, double w)
{
    const double smoothing = wh->sm[i];
    const double s = smoothing > 0.0 ? w / smoothing : copysign(1e9, w);
    const double sat = s > 1.0 ? 1.0 : (s < -1.0 ? -1.0 : s);
    return -wh->cv[i] * w - wh->cc[i] * sat;
}

/* step_with_wheels' wheel_terms: from the stage state x and wheel momenta hs, e = total wheel momentum
 * in B (with the body's constant one) and the wheels' torque on the body; hdot = u + friction. */
static void fl_wheel_terms(const fl_body *bd, const fl_wheels *wh, const double *x, const double *hs,
                           const double *u, double *e, double *hdot)
{
    const double w1 = x[4], w2 = x[5], w3 = x[6];
    double hx = bd->h[0], hy = bd->h[1], hz = bd->h[2];
    double tx = 0.0, ty = 0.0, tz = 0.0;
    for (int i = 0; i < wh->n; i++) {
        const double gx = wh->g[3 * i], gy = wh->g[3 * i + 1], gz = wh->g[3 * i + 2];
        const double hi = hs[i];
        hx += hi * gx;
        hy += hi * gy;
        hz += hi * gz;
        const double d = u[i] + fl_friction(wh, i, hi / wh->js[i] - (gx * w1 + gy * w2 + gz * w3));
        hdot[i] = d;
        tx -= d * gx;
        ty -= d * gy;
        tz -= d * gz;
    }
    e[0] = hx; e[1] = hy; e[2] = hz; e[3] = tx; e[4] = ty; e[5] = tz;
}

/* control.quaternion.rotate_n_to_b: out = [BN(q)] v. */
static void fl_rotate_n_to_b(const double *q, const double *v, double *out)
{
    const double q0 = q[0], q1 = q[1], q2 = q[2], q3 = q[3];
    const double x = v[0], y = v[1], z = v[2];
    const double q00 = q0 * q0, q11 = q1 * q1, q22 = q2 * q2, q33 = q3 * q3;
    const double q01 = q0 * q1, q02 = q0 * q2, q03 = q0 * q3, q12 = q1 * q2, q13 = q1 * q3, q23 = q2 * q3;
    out[0] = (q00 + q11 - q22 - q33) * x + 2.0 * ((q12 + q03) * y + (q13 - q02) * z);
    out[1] = (q00 - q11 + q22 - q33) * y + 2.0 * ((q12 - q03) * x + (q23 + q01) * z);
    out[2] = (q00 - q11 - q22 + q33) * z + 2.0 * ((q13 + q02) * x + (q23 - q01) * y);
}

/* wheels.step_with_wheels: one RK4 step of body + wheel momenta with the motor torques u held and, when tau
 * is not NULL, the external body torque tau (N m, B; step_with_wheels' torque_B) held too.
 * st[7], h[n] in; out[7] (state), h_out[n] (N m s) out. */
static void fl_step_wheels(const fl_body *bd, const fl_wheels *wh, const double *st, const double *h,
                           const double *u, double dt, const double *m_B, const double *b_N, double g,
                           const double *r_hat_N, const double *tau, double *out, double *h_out)
{
    const int n = wh->n;
    double x0[13], k[4][13];
    for (int j = 0; j < 7; j++)
        x0[j] = st[j];
    fl_rotate_n_to_b(st, b_N, x0 + 7);
    fl_rotate_n_to_b(st, r_hat_N, x0 + 10);
    if (!wh->friction) {
        /* h_dot = u is constant over the step: the wheel momentum is linear in time */
        const double a = 0.5 * dt;
        double hx = bd->h[0], hy = bd->h[1], hz = bd->h[2];
        double ux = 0.0, uy = 0.0, uz = 0.0;
        for (int i = 0; i < n; i++) {
            const double gx = wh->g[3 * i], gy = wh->g[3 * i + 1], gz = wh->g[3 * i + 2];
            hx += h[i] * gx;
            hy += h[i] * gy;
            hz += h[i] * gz;
            ux += u[i] * gx;
            uy += u[i] * gy;
            uz += u[i] * gz;
        }
        const double hw[4][3] = {{hx, hy, hz}, {hx + a * ux, hy + a * uy, hz + a * uz},
                                 {hx + a * ux, hy + a * uy, hz + a * uz}, {hx + dt * ux, hy + dt * uy, hz + dt * uz}};
        double t[3] = {-ux, -uy, -uz};
        if (tau != NULL) {
            t[0] = tau[0] - ux;
            t[1] = tau[1] - uy;
            t[2] = tau[2] - uz;
        }
        fl_rk4_stages(bd, x0, dt, hw, t, m_B, g, k);
        for (int i = 0; i < n; i++)
            h_out[i] = h[i] + u[i] * dt;
    } else {
        /* friction depends on the stage's wheel speed: the wheel momenta are stage states too */
        const double step[4] = {0.0, 0.5 * dt, 0.5 * dt, dt};
        const double c = dt / 6.0;
        double xa[13], e[6], hs[FL_MAX_WHEELS], l[4][FL_MAX_WHEELS];
        fl_wheel_terms(bd, wh, x0, h, u, e, l[0]);
        if (tau != NULL) {
            e[3] = e[3] + tau[0];
            e[4] = e[4] + tau[1];
            e[5] = e[5] + tau[2];
        }
        fl_stage_deriv(bd, x0, e[0], e[1], e[2], e[3], e[4], e[5], m_B, g, k[0]);
        for (int s = 1; s < 4; s++) {
            for (int j = 0; j < 13; j++)
                xa[j] = x0[j] + step[s] * k[s - 1][j];
            for (int i = 0; i < n; i++)
                hs[i] = h[i] + step[s] * l[s - 1][i];
            fl_wheel_terms(bd, wh, xa, hs, u, e, l[s]);
            if (tau != NULL) {
                e[3] = e[3] + tau[0];
                e[4] = e[4] + tau[1];
                e[5] = e[5] + tau[2];
            }
            fl_stage_deriv(bd, xa, e[0], e[1], e[2], e[3], e[4], e[5], m_B, g, k[s]);
        }
        for (int i = 0; i < n; i++)
            h_out[i] = h[i] + c * (l[0][i] + 2.0 * (l[1][i] + l[2][i]) + l[3][i]);
    }
    fl_rk4_combine(x0, (const double (*)[13])k, dt, out);
}

/* --- the electrical system and the thermal model (power.py ElectricalSystem.step with its solar_power_w,
 * thermal.py ThermalModel.step). Powers W, energies J, dt s, temperatures K, flux W/m^2; s_N the Sun's unit
 * direction in N, r_N metres, q the attitude q_BN. The constants, in the order plant_kernel.power_constants
 * gives them: */
enum { PC_EARTH_R, PC_SOLAR_CONST, PC_AREA0, PC_EFF = PC_AREA0 + 6, PC_R_INT, PC_CELLS, PC_CAPACITY_J,
       PC_ALPHA, PC_FACE_AREA, PC_EMISSIVITY, PC_SIGMA, PC_C_FACE, PC_C_INTERIOR, PC_G, PC_MAX_SUBSTEP, PC_N };

static const double fl_ocv_table[11] = {3.00, 3.45, 3.58, 3.66, 3.72, 3.78, 3.86, 3.94, 4.02, 4.10, 4.20};

/* power.cell_ocv */
static double fl_cell_ocv(double soc)
{
    if (soc <= 0.0)
        return fl_ocv_table[0];
    if (soc >= 1.0)
        return fl_ocv_table[10];
    const double x = soc * 10.0;
    const int k = (int)x;
    return fl_ocv_table[k] + (x - (double)k) * (fl_ocv_table[k + 1] - fl_ocv_table[k]);
}

/* ElectricalSystem.solar_power_w (sun.in_umbra inlined) with the Sun (s_N, d_au) given: the array's W, the
 * face fluxes into flux[6]; *eclipse set. */
static double fl_solar_power(const double *c, const double *q, const double *r, const double *s, double d_au,
                             double *flux, int *eclipse)
{
    const double along = r[0] * s[0] + r[1] * s[1] + r[2] * s[2];
    if (!(along >= 0.0)) {
        const double px = r[0] - along * s[0], py = r[1] - along * s[1], pz = r[2] - along * s[2];
        if (px * px + py * py + pz * pz < c[PC_EARTH_R] * c[PC_EARTH_R]) {
            *eclipse = 1;
            for (int i = 0; i < 6; i++)
                flux[i] = 0.0;
            return 0.0;
        }
    }
    *eclipse = 0;
    double sb[3], cs[6];
    fl_rotate_n_to_b(q, s, sb);
    const double f = c[PC_SOLAR_CONST] / (d_au * d_au);
    for (int i = 0; i < 3; i++) {
        const double v = sb[i];
        cs[2 * i] = v > 0.0 ? v : 0.0;
        cs[2 * i + 1] = v > 0.0 ? 0.0 : (v < 0.0 ? -v : 0.0);
    }
    for (int i = 0; i < 6; i++)
        flux[i] = f * cs[i];
    const double *a = c + PC_AREA0;
    const double lit = a[0] * cs[0] + a[1] * cs[1] + a[2] * cs[2] + a[3] * cs[3] + a[4] * cs[4] + a[5] * cs[5];
    return f * c[PC_EFF] * lit;
}

/* ElectricalSystem.step then ThermalModel.step over dt > 0 s. acc[7] in and out: battery energy, then the
 * solar, shunted, load, coil, loss and unserved energies (J); faces[6] and *interior (K) in and out;
 * out[5]: solar W, load W, battery current A, terminal V, eclipse (0/1); flux[6] out. */
static void fl_power_step(const double *c, double dt, const double *q, const double *r, const double *s,
                          double d_au, double coil_w, double load_sw, double *acc, double *faces,
                          double *interior, double *out, double *flux)
{
    int eclipse;
    const double solar = fl_solar_power(c, q, r, s, d_au, flux, &eclipse);
    const double load = load_sw + coil_w;
    const double rr = c[PC_R_INT], cap = c[PC_CAPACITY_J];
    double energy = acc[0];
    double net = load - solar;
    double shunted = 0.0, unserved = 0.0, current;
    if (net < 0.0 && energy >= cap) {
        shunted = -net;
        net = 0.0;
    }
    const double ocv = fl_cell_ocv(energy / cap) * c[PC_CELLS];
    if (net != 0.0) {  /* Battery.current_for_ocv */
        if (rr <= 0.0) {
            current = net / ocv;
        } else {
            const double disc = ocv * ocv - 4.0 * rr * net;
            current = disc < 0.0 ? ocv / (2.0 * rr) : (ocv - sqrt(disc)) / (2.0 * rr);
        }
    } else {
        current = 0.0;
    }
    const double delivered = (ocv - current * rr) * current;
    if (net > 0.0 && delivered < net)
        unserved = net - delivered;
    const double d_e = -ocv * current * dt;
    const double loss = current * current * rr * dt;
    double new_e = energy + d_e;
    if (new_e > cap) {
        const double excess = new_e - cap;
        shunted += excess / dt;
        new_e = cap;
    } else if (new_e < 0.0) {
        unserved += -new_e / dt;
        new_e = 0.0;
    }
    acc[0] = new_e;
    acc[1] += solar * dt;
    acc[2] += shunted * dt;
    acc[3] += load * dt;
    acc[4] += coil_w * dt;
    acc[5] += loss;
    acc[6] += unserved * dt;
    out[0] = solar;
    out[1] = load;
    out[2] = current;
    out[3] = new_e > 0.0 ? ocv - current * rr : 0.0;
    out[4] = eclipse;
    /* ThermalModel.step with face_flux_w_m2 = flux, load_w = load */
    long long n = (long long)(dt / c[PC_MAX_SUBSTEP] + 0.999999);
    if (n < 1)
        n = 1;
    const double h = dt / (double)n;
    const double a = c[PC_FACE_AREA], g = c[PC_G];
    double absorbed[6];
    for (int f = 0; f < 6; f++)
        absorbed[f] = c[PC_ALPHA] * a * flux[f];
    const double rad = c[PC_EMISSIVITY] * c[PC_SIGMA] * a;
    const double c_face = c[PC_C_FACE], c_interior = c[PC_C_INTERIOR];
    for (long long k = 0; k < n; k++) {
        const double ti = *interior;
        double to_interior = 0.0;
        for (int f = 0; f < 6; f++) {
            const double tf = faces[f];
            const double cond = g * (tf - ti);
            to_interior += cond;
            faces[f] = tf + h * (absorbed[f] - rad * pow(tf, 4.0) - cond) / c_face;
        }
        *interior = ti + h * (load + to_interior) / c_interior;
    }
}

/* --- Python boundary ------------------------------------------------------------------------------ */

/* A tuple of n numbers into v; a TypeError naming `what` otherwise. */
static int read_floats(PyObject *obj, double *v, Py_ssize_t n, const char *what)
{
    if (!PyTuple_Check(obj) || PyTuple_GET_SIZE(obj) != n) {
        PyErr_Format(PyExc_TypeError, "%s must be a tuple of %zd floats", what, n);
        return -1;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *x = PyTuple_GET_ITEM(obj, i);
        if (PyFloat_CheckExact(x)) {
            v[i] = PyFloat_AS_DOUBLE(x);
        } else {
            v[i] = PyFloat_AsDouble(x);
            if (v[i] == -1.0 && PyErr_Occurred())
                return -1;
        }
    }
    return 0;
}

static int read_float(PyObject *obj, double *v)
{
    *v = PyFloat_CheckExact(obj) ? PyFloat_AS_DOUBLE(obj) : PyFloat_AsDouble(obj);
    return (*v == -1.0 && PyErr_Occurred()) ? -1 : 0;
}

static PyObject *float_tuple(const double *v, Py_ssize_t n)
{
    PyObject *t = PyTuple_New(n);
    if (t == NULL)
        return NULL;
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *x = PyFloat_FromDouble(v[i]);
        if (x == NULL) {
            Py_DECREF(t);
            return NULL;
        }
        PyTuple_SET_ITEM(t, i, x);
    }
    return t;
}

static int check_nargs(Py_ssize_t got, Py_ssize_t lo, Py_ssize_t hi, const char *name)
{
    if (got < lo || got > hi) {
        PyErr_Format(PyExc_TypeError, "%s takes %zd to %zd arguments (%zd given)", name, lo, hi, got);
        return -1;
    }
    return 0;
}

/* Kernel(inertia9, inertia_inv9, wheel_momentum3[, environment[, wheels]]): one plant's constants. */
typedef struct {
    PyObject_HEAD
    fl_body body;
    char has_env;
    char has_wheels;
    char wheel_friction;
    int wheel_count;
    fl_env env;
    fl_wheels wheels;
} KernelObject;

static void Kernel_dealloc(KernelObject *self)
{
    Py_CLEAR(self->env.node_fn);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static PyMemberDef Kernel_members[] = {
    {"has_environment", T_BOOL, offsetof(KernelObject, has_env), READONLY,
     "whether environment(), step() and step_wheels_env() are available (made with the environment constants)"},
    {"has_wheels", T_BOOL, offsetof(KernelObject, has_wheels), READONLY,
     "whether step_wheels() and step_wheels_env() are available (made with the wheel constants)"},
    {"wheel_friction", T_BOOL, offsetof(KernelObject, wheel_friction), READONLY,
     "whether any wheel has bearing friction (WheelAssembly.friction: the RK4 then integrates it)"},
    {"wheel_count", T_INT, offsetof(KernelObject, wheel_count), READONLY, "number of wheels (0 without)"},
    {NULL, 0, 0, 0, NULL},
};

/* environment: the 7 CircularOrbit constants, then the field's: 5 for the dipole (12 in all), the 3
 * components of b_O for the orbit-constant field (10 in all), or the table step and the node callable
 * (9 in all); plant_kernel.environment_parameters. */
static int read_env(PyObject *env, fl_env *e)
{
    double p[12];
    Py_ssize_t n = PyTuple_Check(env) ? PyTuple_GET_SIZE(env) : -1;
    if (n != 12 && n != 10 && n != 9) {
        PyErr_SetString(PyExc_TypeError, "environment must be a tuple of 12 floats (circular orbit + dipole), "
                                         "10 (circular orbit + orbit-constant field) or 8 floats and a callable "
                                         "(circular orbit + tabulated field)");
        return -1;
    }
    if (n == 9) {
        PyObject *fn = PyTuple_GET_ITEM(env, 8);
        PyObject *head = PyTuple_GetSlice(env, 0, 8);
        int bad = head == NULL || read_floats(head, p, 8, "environment (orbit and table step)");
        Py_XDECREF(head);
        if (bad)
            return -1;
        if (!PyCallable_Check(fn) || !(p[7] > 0.0)) {
            PyErr_SetString(PyExc_TypeError, "a tabulated field needs a table step > 0 and a callable node(k)");
            return -1;
        }
        Py_INCREF(fn);
        Py_XSETREF(e->node_fn, fn);
        e->field = FL_FIELD_TABLE;
        e->table_step = p[7];
        e->nodes_held = 0;
    } else if (read_floats(env, p, n, "environment"))
        return -1;
    e->a = p[0]; e->u0 = p[1]; e->u_rate = p[2]; e->raan0 = p[3]; e->raan_rate = p[4]; e->ci = p[5];
    e->si = p[6];
    if (n == 9) {
        /* set above */
    } else if (n == 12) {
        e->field = FL_FIELD_DIPOLE;
        e->theta0 = p[7]; e->earth_rate = p[8]; e->dx = p[9]; e->dy = p[10]; e->dz = p[11];
    } else {
        e->field = FL_FIELD_ORBIT_CONSTANT;
        e->b_O[0] = p[7]; e->b_O[1] = p[8]; e->b_O[2] = p[9];
    }
    return 0;
}

/* wheels: a tuple of one 7-tuple per wheel, (gx, gy, gz, J_s, c_v, c_c, Omega_s); the friction switch is
 * WheelAssembly.friction's rule (any c_v > 0 or c_c > 0). */
static int read_wheels(PyObject *wheels, fl_wheels *wh)
{
    if (!PyTuple_Check(wheels) || PyTuple_GET_SIZE(wheels) < 1 || PyTuple_GET_SIZE(wheels) > FL_MAX_WHEELS) {
        PyErr_Format(PyExc_TypeError, "wheels must be a tuple of 1 to %d wheels", FL_MAX_WHEELS);
        return -1;
    }
    wh->n = (int)PyTuple_GET_SIZE(wheels);
    wh->friction = 0;
    for (int i = 0; i < wh->n; i++) {
        double p[7];
        if (read_floats(PyTuple_GET_ITEM(wheels, i), p, 7, "wheel (gx, gy, gz, J_s, c_v, c_c, Omega_s)"))
            return -1;
        wh->g[3 * i] = p[0]; wh->g[3 * i + 1] = p[1]; wh->g[3 * i + 2] = p[2];
        wh->js[i] = p[3]; wh->cv[i] = p[4]; wh->cc[i] = p[5]; wh->sm[i] = p[6];
        if (p[4] > 0.0 || p[5] > 0.0)
            wh->friction = 1;
    }
    return 0;
}

static int Kernel_init(KernelObject *self, PyObject *args, PyObject *kwds)
{
    PyObject *j, *ji, *h, *env = Py_None, *wheels = Py_None;
    if (kwds != NULL && PyDict_GET_SIZE(kwds) != 0) {
        PyErr_SetString(PyExc_TypeError, "Kernel takes positional arguments only");
        return -1;
    }
    if (!PyArg_UnpackTuple(args, "Kernel", 3, 5, &j, &ji, &h, &env, &wheels))
        return -1;
    if (read_floats(j, self->body.j, 9, "inertia") || read_floats(ji, self->body.ji, 9, "inertia_inv")
        || read_floats(h, self->body.h, 3, "wheel_momentum_B"))
        return -1;
    self->has_env = 0;
    self->has_wheels = 0;
    self->wheel_friction = 0;
    self->wheel_count = 0;
    if (env != Py_None) {
        if (read_env(env, &self->env))
            return -1;
        self->has_env = 1;
    }
    if (wheels != Py_None) {
        if (read_wheels(wheels, &self->wheels))
            return -1;
        self->has_wheels = 1;
        self->wheel_friction = (char)self->wheels.friction;
        self->wheel_count = self->wheels.n;
    }
    return 0;
}

/* step_env(state, dt, m_B, b_N, gg, r_hat_N[, torque_B]) -> state */
static PyObject *Kernel_step_env(KernelObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    double st[7], m[3], b[3], r[3], tau[3] = {0.0, 0.0, 0.0}, out[7], dt, g;
    if (check_nargs(nargs, 6, 7, "step_env")
        || read_floats(args[0], st, 7, "state") || read_float(args[1], &dt)
        || read_floats(args[2], m, 3, "m_B") || read_floats(args[3], b, 3, "b_N") || read_float(args[4], &g)
        || read_floats(args[5], r, 3, "r_hat_N") || (nargs == 7 && read_floats(args[6], tau, 3, "torque_B")))
        return NULL;
    fl_step_env(&self->body, st, dt, m, b, g, r, tau, out);
    return float_tuple(out, 7);
}

static int need_env(KernelObject *self)
{
    if (!self->has_env) {
        PyErr_SetString(PyExc_ValueError, "this kernel was made without an environment (a circular orbit with the dipole, "
                                         "the orbit-constant field or a tabulated field)");
        return -1;
    }
    return 0;
}

/* (r_N, r_hat_N, b_N) as three 3-tuples; steals nothing. */
static PyObject *env_tuples(const double *e)
{
    PyObject *r = float_tuple(e, 3);
    PyObject *rh = r ? float_tuple(e + 3, 3) : NULL;
    PyObject *b = rh ? float_tuple(e + 6, 3) : NULL;
    PyObject *out = b ? PyTuple_Pack(3, r, rh, b) : NULL;
    Py_XDECREF(r);
    Py_XDECREF(rh);
    Py_XDECREF(b);
    return out;
}

/* environment(t) -> (r_N, r_hat_N, b_N) */
static PyObject *Kernel_environment(KernelObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    double t, e[9];
    if (check_nargs(nargs, 1, 1, "environment") || need_env(self) || read_float(args[0], &t))
        return NULL;
    if (fl_environment(&self->env, t, e))
        return NULL;
    return env_tuples(e);
}

/* step(state, dt, m_B, b_N, gg, r_hat_N, t1[, torque_B]) -> (state1, r_N, r_hat_N, b_N): step_env, then the
 * environment at the step's end t1 (what Plant.step_ns does with the two). */
static PyObject *Kernel_step(KernelObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    double tau[3] = {0.0, 0.0, 0.0};
    double st[7], m[3], b[3], r[3], out[7], e[9], dt, g, t1;
    if (check_nargs(nargs, 7, 8, "step") || need_env(self)
        || read_floats(args[0], st, 7, "state") || read_float(args[1], &dt)
        || read_floats(args[2], m, 3, "m_B") || read_floats(args[3], b, 3, "b_N") || read_float(args[4], &g)
        || read_floats(args[5], r, 3, "r_hat_N") || read_float(args[6], &t1)
        || (nargs == 8 && read_floats(args[7], tau, 3, "torque_B")))
        return NULL;
    fl_step_env(&self->body, st, dt, m, b, g, r, tau, out);
    if (fl_environment(&self->env, t1, e))
        return NULL;
    PyObject *s = float_tuple(out, 7);
    PyObject *rn = s ? float_tuple(e, 3) : NULL;
    PyObject *rh = rn ? float_tuple(e + 3, 3) : NULL;
    PyObject *bn = rh ? float_tuple(e + 6, 3) : NULL;
    PyObject *res = bn ? PyTuple_Pack(4, s, rn, rh, bn) : NULL;
    Py_XDECREF(s);
    Py_XDECREF(rn);
    Py_XDECREF(rh);
    Py_XDECREF(bn);
    return res;
}

static int need_wheels(KernelObject *self)
{
    if (!self->has_wheels) {
        PyErr_SetString(PyExc_ValueError, "this kernel was made without wheels");
        return -1;
    }
    return 0;
}

/* The arguments step_wheels and step_wheels_env share: state, h, u, dt, m_B, b_N, gg, r_hat_N. */
static int read_wheel_args(KernelObject *self, PyObject *const *args, double *st, double *h, double *u,
                           double *dt, double *m, double *b, double *g, double *r)
{
    const Py_ssize_t n = self->wheels.n;
    return read_floats(args[0], st, 7, "state") || read_floats(args[1], h, n, "wheel momenta h")
        || read_floats(args[2], u, n, "motor torques u") || read_float(args[3], dt)
        || read_floats(args[4], m, 3, "m_B") || read_floats(args[5], b, 3, "b_N") || read_float(args[6], g)
        || read_floats(args[7], r, 3, "r_hat_N") ? -1 : 0;
}

/* step_wheels(state, h, u, dt, m_B, b_N, gg, r_hat_N[, torque_B]) -> (state1, h1): wheels.step_with_wheels */
static PyObject *Kernel_step_wheels(KernelObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    double st[7], h[FL_MAX_WHEELS], u[FL_MAX_WHEELS], m[3], b[3], r[3], out[7], h1[FL_MAX_WHEELS], dt, g, tau[3];
    if (check_nargs(nargs, 8, 9, "step_wheels") || need_wheels(self)
        || read_wheel_args(self, args, st, h, u, &dt, m, b, &g, r)
        || (nargs == 9 && read_floats(args[8], tau, 3, "torque_B")))
        return NULL;
    fl_step_wheels(&self->body, &self->wheels, st, h, u, dt, m, b, g, r, nargs == 9 ? tau : NULL, out, h1);
    PyObject *s = float_tuple(out, 7);
    PyObject *hh = s ? float_tuple(h1, self->wheels.n) : NULL;
    PyObject *res = hh ? PyTuple_Pack(2, s, hh) : NULL;
    Py_XDECREF(s);
    Py_XDECREF(hh);
    return res;
}

/* step_wheels_env(state, h, u, dt, m_B, b_N, gg, r_hat_N, t1[, torque_B]) -> (state1, h1, r_N, r_hat_N, b_N):
 * step_wheels, then the environment at the step's end t1 (Plant.step_ns with wheels). */
static PyObject *Kernel_step_wheels_env(KernelObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    double st[7], h[FL_MAX_WHEELS], u[FL_MAX_WHEELS], m[3], b[3], r[3], out[7], h1[FL_MAX_WHEELS], e[9];
    double dt, g, t1, tau[3];
    if (check_nargs(nargs, 9, 10, "step_wheels_env") || need_wheels(self) || need_env(self)
        || read_wheel_args(self, args, st, h, u, &dt, m, b, &g, r) || read_float(args[8], &t1)
        || (nargs == 10 && read_floats(args[9], tau, 3, "torque_B")))
        return NULL;
    fl_step_wheels(&self->body, &self->wheels, st, h, u, dt, m, b, g, r, nargs == 10 ? tau : NULL, out, h1);
    if (fl_environment(&self->env, t1, e))
        return NULL;
    PyObject *s = float_tuple(out, 7);
    PyObject *hh = s ? float_tuple(h1, self->wheels.n) : NULL;
    PyObject *rn = hh ? float_tuple(e, 3) : NULL;
    PyObject *rh = rn ? float_tuple(e + 3, 3) : NULL;
    PyObject *bn = rh ? float_tuple(e + 6, 3) : NULL;
    PyObject *res = bn ? PyTuple_Pack(5, s, hh, rn, rh, bn) : NULL;
    Py_XDECREF(s);
    Py_XDECREF(hh);
    Py_XDECREF(rn);
    Py_XDECREF(rh);
    Py_XDECREF(bn);
    return res;
}

/* Reads n floats from a tuple or a list of n (the wheels' commands and limits, a sensor's constants). */
static int read_seq(PyObject *obj, double *v, Py_ssize_t n, const char *what)
{
    if (PyTuple_Check(obj))
        return read_floats(obj, v, n, what);
    if (!PyList_Check(obj) || PyList_GET_SIZE(obj) != n) {
        PyErr_Format(PyExc_TypeError, "%s must be %zd floats", what, n);
        return -1;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        if (read_float(PyList_GET_ITEM(obj, i), v + i) < 0)
            return -1;
    }
    return 0;
}

/* motor_torques(dt, omega_B, h, mode, speed, enabled, command, u_max, h_max, tau_s, clipped, limited) -> u:
 * WheelAssembly.motor_torques with this kernel's wheel constants (axes, inertias, friction). ``mode`` and
 * ``enabled`` are the assembly's lists (a wheel whose mode equals ``speed`` runs its speed loop), ``tau_s``
 * the speed loops' time constants; ``clipped`` and ``limited`` (lists) are set in place as the Python sets
 * torque_clipped and momentum_limited. Returns the limited motor torques (N m) as a tuple. */
static PyObject *Kernel_motor_torques(KernelObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    double dt, w[3], h[FL_MAX_WHEELS], cmd[FL_MAX_WHEELS], umax[FL_MAX_WHEELS], hmax[FL_MAX_WHEELS],
        taus[FL_MAX_WHEELS], out[FL_MAX_WHEELS];
    if (check_nargs(nargs, 12, 12, "motor_torques") || need_wheels(self))
        return NULL;
    const fl_wheels *wh = &self->wheels;
    const Py_ssize_t n = wh->n;
    PyObject *mode = args[3], *speed = args[4], *enabled = args[5], *clipped = args[10], *limited = args[11];
    if (read_float(args[0], &dt) || read_seq(args[1], w, 3, "omega_B") || read_seq(args[2], h, n, "h")
        || read_seq(args[6], cmd, n, "command") || read_seq(args[7], umax, n, "u_max")
        || read_seq(args[8], hmax, n, "h_max") || read_seq(args[9], taus, n, "tau_s"))
        return NULL;
    if (!PyList_Check(mode) || PyList_GET_SIZE(mode) != n || !PyList_Check(enabled) || PyList_GET_SIZE(enabled) != n
        || !PyList_Check(clipped) || PyList_GET_SIZE(clipped) != n || !PyList_Check(limited)
        || PyList_GET_SIZE(limited) != n) {
        PyErr_Format(PyExc_TypeError, "mode, enabled, clipped and limited must be lists of %zd", n);
        return NULL;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        const int on = PyObject_IsTrue(PyList_GET_ITEM(enabled, i));
        if (on < 0)
            return NULL;
        if (!on) {
            out[i] = 0.0;
            PyList_SetItem(clipped, i, Py_NewRef(Py_False));
            PyList_SetItem(limited, i, Py_NewRef(Py_False));
            continue;
        }
        const int speed_mode = PyObject_RichCompareBool(PyList_GET_ITEM(mode, i), speed, Py_EQ);
        if (speed_mode < 0)
            return NULL;
        const double gx = wh->g[3 * i], gy = wh->g[3 * i + 1], gz = wh->g[3 * i + 2];
        /* speed_rad_s(i, omega_B), taken for the speed loop or the friction (both uses: the same value) */
        const double spd = (speed_mode || wh->friction) ? h[i] / wh->js[i] - (gx * w[0] + gy * w[1] + gz * w[2])
                                                        : 0.0;
        double u;
        if (speed_mode) {
            const double tau = 2.0 * dt > taus[i] ? 2.0 * dt : taus[i];  /* max(time constant, 2 dt) */
            u = wh->js[i] * (cmd[i] - spd) / tau;
        } else {
            u = cmd[i];
        }
        const double um = umax[i];
        const int clip = u > um || u < -um;
        if (clip)
            u = u > 0.0 ? um : -um;
        const double hi = h[i], hm = hmax[i];
        int lim = 0;
        const double f0 = wh->friction ? fl_friction(wh, (int)i, spd) : 0.0;
        const double h1 = hi + (u + f0) * dt;
        if (h1 > hm && u > 0.0) {
            const double x = (hm - hi) / dt - f0;
            u = x > 0.0 ? x : 0.0;  /* max(0.0, x) */
            lim = 1;
        } else if (h1 < -hm && u < 0.0) {
            const double x = (-hm - hi) / dt - f0;
            u = x < 0.0 ? x : 0.0;  /* min(0.0, x) */
            lim = 1;
        }
        PyList_SetItem(clipped, i, Py_NewRef(clip && !speed_mode ? Py_True : Py_False));
        PyList_SetItem(limited, i, Py_NewRef(lim ? Py_True : Py_False));
        out[i] = u;
    }
    return float_tuple(out, n);
}

static PyMethodDef Kernel_methods[] = {
    {"motor_torques", (PyCFunction)(void (*)(void))Kernel_motor_torques, METH_FASTCALL,
     "motor_torques(dt, omega_B, h, mode, speed, enabled, command, u_max, h_max, tau_s, clipped, limited) -> u: "
     "WheelAssembly.motor_torques"},
    {"step_env", (PyCFunction)(void (*)(void))Kernel_step_env, METH_FASTCALL,
     "step_env(state, dt, m_B, b_N, gg, r_hat_N[, torque_B]) -> state: RigidBody.step_env"},
    {"environment", (PyCFunction)(void (*)(void))Kernel_environment, METH_FASTCALL,
     "environment(t) -> (r_N, r_hat_N, b_N): the circular orbit and its field at t seconds"},
    {"step", (PyCFunction)(void (*)(void))Kernel_step, METH_FASTCALL,
     "step(state, dt, m_B, b_N, gg, r_hat_N, t1[, torque_B]) -> (state1, r_N, r_hat_N, b_N)"},
    {"step_wheels", (PyCFunction)(void (*)(void))Kernel_step_wheels, METH_FASTCALL,
     "step_wheels(state, h, u, dt, m_B, b_N, gg, r_hat_N[, torque_B]) -> (state1, h1): wheels.step_with_wheels"},
    {"step_wheels_env", (PyCFunction)(void (*)(void))Kernel_step_wheels_env, METH_FASTCALL,
     "step_wheels_env(state, h, u, dt, m_B, b_N, gg, r_hat_N, t1[, torque_B]) -> (state1, h1, r_N, r_hat_N, b_N)"},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject KernelType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "detumble.sim._plant_kernel.Kernel",
    .tp_basicsize = sizeof(KernelObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Kernel(inertia9, inertia_inv9, wheel_momentum_B[, environment[, wheels]]): one plant's "
              "compiled step",
    .tp_methods = Kernel_methods,
    .tp_members = Kernel_members,
    .tp_init = (initproc)Kernel_init,
    .tp_dealloc = (destructor)Kernel_dealloc,
    .tp_new = PyType_GenericNew,
};

/* power_step(constants, dt, q_BN, r_N, s_N, d_au, coil_w, switched_load_w, accumulators7, face_k, interior_k)
 *   -> (eclipse, face_flux6, solar_w, load_w, current_a, terminal_v, accumulators7, interior_k);
 * face_k (a list of 6 floats, K) is updated in place. */
static PyObject *power_step(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    double c[PC_N], dt, q[4], r[3], s[3], d_au, coil_w, load_sw, acc[7], faces[6], interior, out[5], flux[6];
    (void)module;
    if (check_nargs(nargs, 11, 11, "power_step") < 0
        || read_floats(args[0], c, PC_N, "constants") < 0 || read_float(args[1], &dt) < 0
        || read_floats(args[2], q, 4, "q_BN") < 0 || read_floats(args[3], r, 3, "r_N") < 0
        || read_floats(args[4], s, 3, "s_N") < 0 || read_float(args[5], &d_au) < 0
        || read_float(args[6], &coil_w) < 0 || read_float(args[7], &load_sw) < 0
        || read_floats(args[8], acc, 7, "accumulators") < 0 || read_float(args[10], &interior) < 0)
        return NULL;
    PyObject *fl = args[9];
    if (!PyList_Check(fl) || PyList_GET_SIZE(fl) != 6) {
        PyErr_SetString(PyExc_TypeError, "face_k must be a list of 6 floats");
        return NULL;
    }
    for (Py_ssize_t i = 0; i < 6; i++)
        if (read_float(PyList_GET_ITEM(fl, i), &faces[i]) < 0)
            return NULL;
    if (!(dt > 0.0)) {
        PyErr_SetString(PyExc_ValueError, "power_step needs dt > 0");
        return NULL;
    }
    fl_power_step(c, dt, q, r, s, d_au, coil_w, load_sw, acc, faces, &interior, out, flux);
    for (Py_ssize_t i = 0; i < 6; i++) {
        PyObject *x = PyFloat_FromDouble(faces[i]);
        if (x == NULL)
            return NULL;
        PyList_SetItem(fl, i, x);  /* steals x */
    }
    PyObject *ft = float_tuple(flux, 6);
    PyObject *at = ft ? float_tuple(acc, 7) : NULL;
    PyObject *res = at ? Py_BuildValue("(ONddddNd)", out[4] ? Py_True : Py_False, ft, out[0], out[1], out[2],
                                       out[3], at, interior) : NULL;
    if (res == NULL) {
        Py_XDECREF(ft);
        Py_XDECREF(at);
    }
    return res;
}

/* --- sensor samples (sensors.py) ------------------------------------------------------------------ */

/* random.Random.gauss's TWOPI: 2.0 * math.pi */
#define FL_TWOPI (2.0 * 3.141592653589793)

static PyObject *str_gauss_next, *str_random;

/* One rng.random() through the generator's own method (``random_fn``, bound once a sample). */
static int fl_random(PyObject *random_fn, double *out)
{
    PyObject *r = PyObject_CallNoArgs(random_fn);
    if (r == NULL)
        return -1;
    *out = PyFloat_AsDouble(r);
    Py_DECREF(r);
    return (*out == -1.0 && PyErr_Occurred()) ? -1 : 0;
}

/* random.Random.gauss(0.0, sd) with the generator's state (its gauss_next attribute, its random()): the same
 * draws in the same order, and the pair's second half left in gauss_next as gauss leaves it. */
static int fl_gauss(PyObject *rng, PyObject *random_fn, double sd, double *out)
{
    double z;
    PyObject *held = PyObject_GetAttr(rng, str_gauss_next);
    if (held == NULL)
        return -1;
    if (PyObject_SetAttr(rng, str_gauss_next, Py_None) < 0) {
        Py_DECREF(held);
        return -1;
    }
    if (held != Py_None) {
        z = PyFloat_AsDouble(held);
        Py_DECREF(held);
        if (z == -1.0 && PyErr_Occurred())
            return -1;
    } else {
        double r1, r2;
        Py_DECREF(held);
        if (fl_random(random_fn, &r1) < 0 || fl_random(random_fn, &r2) < 0)
            return -1;
        const double x2pi = r1 * FL_TWOPI;
        const double g2rad = sqrt(-2.0 * log(1.0 - r2));
        z = cos(x2pi) * g2rad;
        PyObject *second = PyFloat_FromDouble(sin(x2pi) * g2rad);
        if (second == NULL)
            return -1;
        const int rc = PyObject_SetAttr(rng, str_gauss_next, second);
        Py_DECREF(second);
        if (rc < 0)
            return -1;
    }
    *out = 0.0 + z * sd;  /* gauss's mu + z * sigma */
    return 0;
}

/* sensors._measured's noise and _quantise3: ``v`` (3) plus three gauss draws when sd > 0, then quantised
 * and limited; a value math.floor refuses raises as it does (the draws are made first, as in Python). */
static PyObject *fl_measured(double *v, double sd, double lsb, double limit, PyObject *rng)
{
    if (sd > 0.0) {
        PyObject *random_fn = PyObject_GetAttr(rng, str_random);
        if (random_fn == NULL)
            return NULL;
        for (int i = 0; i < 3; i++) {
            double g;
            if (fl_gauss(rng, random_fn, sd, &g) < 0) {
                Py_DECREF(random_fn);
                return NULL;
            }
            v[i] += g;
        }
        Py_DECREF(random_fn);
    }
    for (int i = 0; i < 3; i++) {
        double x = v[i];
        if (lsb > 0.0) {
            const double y = x / lsb + 0.5;
            if (isnan(y)) {
                PyErr_SetString(PyExc_ValueError, "cannot convert float NaN to integer");
                return NULL;
            }
            if (isinf(y)) {
                PyErr_SetString(PyExc_OverflowError, "cannot convert float infinity to integer");
                return NULL;
            }
            x = floor(y) * lsb;
        }
        v[i] = x > limit ? limit : (x < -limit ? -limit : x);
    }
    return float_tuple(v, 3);
}

/* Reads the first n floats of a tuple of at least n (a plant state: q_BN at 0..3, omega_BN_B at 4..6). */
static int read_prefix(PyObject *obj, double *v, Py_ssize_t at, Py_ssize_t n, const char *what)
{
    if (!PyTuple_Check(obj) || PyTuple_GET_SIZE(obj) < at + n) {
        PyErr_Format(PyExc_TypeError, "%s must be a tuple of at least %zd floats", what, at + n);
        return -1;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        if (read_float(PyTuple_GET_ITEM(obj, at + i), v + i) < 0)
            return -1;
    }
    return 0;
}

/* magnetometer_sample(q0, q1, b0_N, b1_N, s, m_coils_B, g, k, bias, sd, lsb, limit, rng) -> (x, y, z) gauss:
 * sensors.Magnetometer._held_gauss's resolve of the held sample (g: gauss per tesla). */
static PyObject *magnetometer_sample(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    double q0[4], q1[4], b0n[3], b1n[3], s, m[3], g, k[3], bias[3], sd, lsb, limit, b0[3], b1[3], v[3];
    (void)module;
    if (check_nargs(nargs, 13, 13, "magnetometer_sample") < 0
        || read_prefix(args[0], q0, 0, 4, "q0") < 0 || read_prefix(args[1], q1, 0, 4, "q1") < 0
        || read_seq(args[2], b0n, 3, "b0_N") < 0 || read_seq(args[3], b1n, 3, "b1_N") < 0
        || read_float(args[4], &s) < 0 || read_seq(args[5], m, 3, "m_coils_B") < 0 || read_float(args[6], &g) < 0
        || read_seq(args[7], k, 3, "k") < 0 || read_seq(args[8], bias, 3, "bias") < 0
        || read_float(args[9], &sd) < 0 || read_float(args[10], &lsb) < 0 || read_float(args[11], &limit) < 0)
        return NULL;
    fl_rotate_n_to_b(q0, b0n, b0);
    fl_rotate_n_to_b(q1, b1n, b1);
    for (int i = 0; i < 3; i++) {
        const double b = b0[i] + s * (b1[i] - b0[i]);
        v[i] = g * b + k[i] * m[i] + bias[i];  /* the field in gauss + the coils' coupling + the bias */
    }
    return fl_measured(v, sd, lsb, limit, args[12]);
}

/* gyro_sample(s0, s1, s, bias, sd, lsb, limit, rng) -> (x, y, z) rad/s: sensors.Gyro._held_rad_s's resolve
 * (the states' rates, slots 4..6). */
static PyObject *gyro_sample(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    double w0[3], w1[3], s, bias[3], sd, lsb, limit, v[3];
    (void)module;
    if (check_nargs(nargs, 8, 8, "gyro_sample") < 0
        || read_prefix(args[0], w0, 4, 3, "s0") < 0 || read_prefix(args[1], w1, 4, 3, "s1") < 0
        || read_float(args[2], &s) < 0 || read_seq(args[3], bias, 3, "bias") < 0
        || read_float(args[4], &sd) < 0 || read_float(args[5], &lsb) < 0 || read_float(args[6], &limit) < 0)
        return NULL;
    for (int i = 0; i < 3; i++)
        v[i] = (w0[i] + s * (w1[i] - w0[i])) + bias[i];
    return fl_measured(v, sd, lsb, limit, args[7]);
}

static PyMethodDef module_methods[] = {
    {"magnetometer_sample", (PyCFunction)(void (*)(void))magnetometer_sample, METH_FASTCALL,
     "magnetometer_sample(q0, q1, b0_N, b1_N, s, m_coils_B, g, k, bias, sd, lsb, limit, rng) -> (x, y, z) gauss"},
    {"gyro_sample", (PyCFunction)(void (*)(void))gyro_sample, METH_FASTCALL,
     "gyro_sample(s0, s1, s, bias, sd, lsb, limit, rng) -> (x, y, z) rad/s"},
    {"power_step", (PyCFunction)(void (*)(void))power_step, METH_FASTCALL,
     "power_step(constants, dt, q_BN, r_N, s_N, d_au, coil_w, switched_load_w, accumulators, face_k, interior_k)"
     " -> (eclipse, face_flux, solar_w, load_w, current_a, terminal_v, accumulators, interior_k): "
     "ElectricalSystem.step then ThermalModel.step"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef kernel_module = {
    PyModuleDef_HEAD_INIT, "_plant_kernel", "Compiled plant kernel (see detumble.sim.plant_kernel).", -1,
    module_methods, NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__plant_kernel(void)
{
    if (PyType_Ready(&KernelType) < 0)
        return NULL;
    if (str_gauss_next == NULL && (str_gauss_next = PyUnicode_InternFromString("gauss_next")) == NULL)
        return NULL;
    if (str_random == NULL && (str_random = PyUnicode_InternFromString("random")) == NULL)
        return NULL;
    PyObject *m = PyModule_Create(&kernel_module);
    if (m == NULL)
        return NULL;
    Py_INCREF(&KernelType);
    if (PyModule_AddObject(m, "Kernel", (PyObject *)&KernelType) < 0
        || PyModule_AddStringConstant(m, "SOURCE_KEY", FL_SOURCE_KEY) < 0) {
        Py_DECREF(&KernelType);
        Py_DECREF(m);
        return NULL;
    }
    return m;
}

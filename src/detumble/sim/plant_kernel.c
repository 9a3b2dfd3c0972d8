/* Compiled plant kernel: the RK4 step of RigidBody.step_env and the circular-orbit + centred-dipole
 * environment of Plant._update_environment, as a CPython extension module (detumble.sim._plant_kernel).
 *
 * The pure-Python code in attitude.py, orbit.py and field.py is the reference. Every expression below is
 * the reference's, operand for operand and in the same order, so that with IEEE double arithmetic, no
 * contraction into fused multiply-adds (-ffp-contract=off) and the same libm sin/cos/sqrt the
 * interpreter's math module calls, the results are the same floats, bit for bit.
 * detumble.sim.plant_kernel checks that when it loads this module (and refuses it otherwise);
 * tests/detumble/sim/test_plant_kernel.py checks whole trajectories.
 *
 * Units and frames as in the Python: state (q0..q3 scalar first = q_BN, omega_BN_B rad/s), m_B A m^2,
 * b_N tesla, r_hat_N unit, gg 1/s^2, t seconds since the scenario epoch, r_N metres.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <structmember.h>
#include <math.h>

#ifndef FL_SOURCE_KEY
#define FL_SOURCE_KEY "unknown"
#endif

/* --- numerics (no Python objects) ------------------------------------------------------------- */

typedef struct {
    double j[9], ji[9], h[3];          /* inertia, its inverse (row major, kg m^2), constant wheel momentum N m s */
} fl_body;

typedef struct {
    double a, u0, u_rate, raan0, raan_rate, ci, si;   /* CircularOrbit */
    double theta0, earth_rate, dx, dy, dz;            /* DipoleField (dipole vector in T m^3) */
} fl_env;

/* RigidBody.step_env with torque_B = tau. */
static void fl_step_env(const fl_body *bd, const double *st, double dt, const double *m_B, const double *b_N,
                        double g, const double *r_hat_N, const double *tau, double *out)
{
    const double j11 = bd->j[0], j12 = bd->j[1], j13 = bd->j[2];
    const double j21 = bd->j[3], j22 = bd->j[4], j23 = bd->j[5];
    const double j31 = bd->j[6], j32 = bd->j[7], j33 = bd->j[8];
    const double i11 = bd->ji[0], i12 = bd->ji[1], i13 = bd->ji[2];
    const double i21 = bd->ji[3], i22 = bd->ji[4], i23 = bd->ji[5];
    const double i31 = bd->ji[6], i32 = bd->ji[7], i33 = bd->ji[8];
    const double hx = bd->h[0], hy = bd->h[1], hz = bd->h[2];
    const double mx = m_B[0], my = m_B[1], mz = m_B[2];
    const double tx = tau[0], ty = tau[1], tz = tau[2];
    const double q0 = st[0], q1 = st[1], q2 = st[2], q3 = st[3], w1 = st[4], w2 = st[5], w3 = st[6];
    const double c11 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3;
    const double c12 = 2.0 * (q1 * q2 + q0 * q3);
    const double c13 = 2.0 * (q1 * q3 - q0 * q2);
    const double c21 = 2.0 * (q1 * q2 - q0 * q3);
    const double c22 = q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3;
    const double c23 = 2.0 * (q2 * q3 + q0 * q1);
    const double c31 = 2.0 * (q1 * q3 + q0 * q2);
    const double c32 = 2.0 * (q2 * q3 - q0 * q1);
    const double c33 = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3;
    const double bx = b_N[0];
    const double by = b_N[1];
    const double bz = b_N[2];
    const double b1 = c11 * bx + c12 * by + c13 * bz;
    const double b2 = c21 * bx + c22 * by + c23 * bz;
    const double b3 = c31 * bx + c32 * by + c33 * bz;
    const double rx = r_hat_N[0];
    const double ry = r_hat_N[1];
    const double rz = r_hat_N[2];
    const double r1 = c11 * rx + c12 * ry + c13 * rz;
    const double r2 = c21 * rx + c22 * ry + c23 * rz;
    const double r3 = c31 * rx + c32 * ry + c33 * rz;
    const double a = 0.5 * dt;
    /* stage 1 */
    const double s1_1 = j11 * r1 + j12 * r2 + j13 * r3;
    const double s2_1 = j21 * r1 + j22 * r2 + j23 * r3;
    const double s3_1 = j31 * r1 + j32 * r2 + j33 * r3;
    const double h1_1 = j11 * w1 + j12 * w2 + j13 * w3 + hx;
    const double h2_1 = j21 * w1 + j22 * w2 + j23 * w3 + hy;
    const double h3_1 = j31 * w1 + j32 * w2 + j33 * w3 + hz;
    const double g1_1 = tx + my * b3 - mz * b2 + g * (r2 * s3_1 - r3 * s2_1) - (w2 * h3_1 - w3 * h2_1);
    const double g2_1 = ty + mz * b1 - mx * b3 + g * (r3 * s1_1 - r1 * s3_1) - (w3 * h1_1 - w1 * h3_1);
    const double g3_1 = tz + mx * b2 - my * b1 + g * (r1 * s2_1 - r2 * s1_1) - (w1 * h2_1 - w2 * h1_1);
    const double k1_0 = 0.5 * (-q1 * w1 - q2 * w2 - q3 * w3);
    const double k1_1 = 0.5 * (q0 * w1 + q2 * w3 - q3 * w2);
    const double k1_2 = 0.5 * (q0 * w2 - q1 * w3 + q3 * w1);
    const double k1_3 = 0.5 * (q0 * w3 + q1 * w2 - q2 * w1);
    const double k1_4 = i11 * g1_1 + i12 * g2_1 + i13 * g3_1;
    const double k1_5 = i21 * g1_1 + i22 * g2_1 + i23 * g3_1;
    const double k1_6 = i31 * g1_1 + i32 * g2_1 + i33 * g3_1;
    const double k1_7 = b2 * w3 - b3 * w2;
    const double k1_8 = b3 * w1 - b1 * w3;
    const double k1_9 = b1 * w2 - b2 * w1;
    const double k1_10 = r2 * w3 - r3 * w2;
    const double k1_11 = r3 * w1 - r1 * w3;
    const double k1_12 = r1 * w2 - r2 * w1;
    /* stage 2 */
    const double q0_2 = q0 + a * k1_0;
    const double q1_2 = q1 + a * k1_1;
    const double q2_2 = q2 + a * k1_2;
    const double q3_2 = q3 + a * k1_3;
    const double w1_2 = w1 + a * k1_4;
    const double w2_2 = w2 + a * k1_5;
    const double w3_2 = w3 + a * k1_6;
    const double b1_2 = b1 + a * k1_7;
    const double b2_2 = b2 + a * k1_8;
    const double b3_2 = b3 + a * k1_9;
    const double r1_2 = r1 + a * k1_10;
    const double r2_2 = r2 + a * k1_11;
    const double r3_2 = r3 + a * k1_12;
    const double s1_2 = j11 * r1_2 + j12 * r2_2 + j13 * r3_2;
    const double s2_2 = j21 * r1_2 + j22 * r2_2 + j23 * r3_2;
    const double s3_2 = j31 * r1_2 + j32 * r2_2 + j33 * r3_2;
    const double h1_2 = j11 * w1_2 + j12 * w2_2 + j13 * w3_2 + hx;
    const double h2_2 = j21 * w1_2 + j22 * w2_2 + j23 * w3_2 + hy;
    const double h3_2 = j31 * w1_2 + j32 * w2_2 + j33 * w3_2 + hz;
    const double g1_2 = tx + my * b3_2 - mz * b2_2 + g * (r2_2 * s3_2 - r3_2 * s2_2) - (w2_2 * h3_2 - w3_2 * h2_2);
    const double g2_2 = ty + mz * b1_2 - mx * b3_2 + g * (r3_2 * s1_2 - r1_2 * s3_2) - (w3_2 * h1_2 - w1_2 * h3_2);
    const double g3_2 = tz + mx * b2_2 - my * b1_2 + g * (r1_2 * s2_2 - r2_2 * s1_2) - (w1_2 * h2_2 - w2_2 * h1_2);
    const double k2_0 = 0.5 * (-q1_2 * w1_2 - q2_2 * w2_2 - q3_2 * w3_2);
    const double k2_1 = 0.5 * (q0_2 * w1_2 + q2_2 * w3_2 - q3_2 * w2_2);
    const double k2_2 = 0.5 * (q0_2 * w2_2 - q1_2 * w3_2 + q3_2 * w1_2);
    const double k2_3 = 0.5 * (q0_2 * w3_2 + q1_2 * w2_2 - q2_2 * w1_2);
    const double k2_4 = i11 * g1_2 + i12 * g2_2 + i13 * g3_2;
    const double k2_5 = i21 * g1_2 + i22 * g2_2 + i23 * g3_2;
    const double k2_6 = i31 * g1_2 + i32 * g2_2 + i33 * g3_2;
    const double k2_7 = b2_2 * w3_2 - b3_2 * w2_2;
    const double k2_8 = b3_2 * w1_2 - b1_2 * w3_2;
    const double k2_9 = b1_2 * w2_2 - b2_2 * w1_2;
    const double k2_10 = r2_2 * w3_2 - r3_2 * w2_2;
    const double k2_11 = r3_2 * w1_2 - r1_2 * w3_2;
    const double k2_12 = r1_2 * w2_2 - r2_2 * w1_2;
    /* stage 3 */
    const double q0_3 = q0 + a * k2_0;
    const double q1_3 = q1 + a * k2_1;
    const double q2_3 = q2 + a * k2_2;
    const double q3_3 = q3 + a * k2_3;
    const double w1_3 = w1 + a * k2_4;
    const double w2_3 = w2 + a * k2_5;
    const double w3_3 = w3 + a * k2_6;
    const double b1_3 = b1 + a * k2_7;
    const double b2_3 = b2 + a * k2_8;
    const double b3_3 = b3 + a * k2_9;
    const double r1_3 = r1 + a * k2_10;
    const double r2_3 = r2 + a * k2_11;
    const double r3_3 = r3 + a * k2_12;
    const double s1_3 = j11 * r1_3 + j12 * r2_3 + j13 * r3_3;
    const double s2_3 = j21 * r1_3 + j22 * r2_3 + j23 * r3_3;
    const double s3_3 = j31 * r1_3 + j32 * r2_3 + j33 * r3_3;
    const double h1_3 = j11 * w1_3 + j12 * w2_3 + j13 * w3_3 + hx;
    const double h2_3 = j21 * w1_3 + j22 * w2_3 + j23 * w3_3 + hy;
    const double h3_3 = j31 * w1_3 + j32 * w2_3 + j33 * w3_3 + hz;
    const double g1_3 = tx + my * b3_3 - mz * b2_3 + g * (r2_3 * s3_3 - r3_3 * s2_3) - (w2_3 * h3_3 - w3_3 * h2_3);
    const double g2_3 = ty + mz * b1_3 - mx * b3_3 + g * (r3_3 * s1_3 - r1_3 * s3_3) - (w3_3 * h1_3 - w1_3 * h3_3);
    const double g3_3 = tz + mx * b2_3 - my * b1_3 + g * (r1_3 * s2_3 - r2_3 * s1_3) - (w1_3 * h2_3 - w2_3 * h1_3);
    const double k3_0 = 0.5 * (-q1_3 * w1_3 - q2_3 * w2_3 - q3_3 * w3_3);
    const double k3_1 = 0.5 * (q0_3 * w1_3 + q2_3 * w3_3 - q3_3 * w2_3);
    const double k3_2 = 0.5 * (q0_3 * w2_3 - q1_3 * w3_3 + q3_3 * w1_3);
    const double k3_3 = 0.5 * (q0_3 * w3_3 + q1_3 * w2_3 - q2_3 * w1_3);
    const double k3_4 = i11 * g1_3 + i12 * g2_3 + i13 * g3_3;
    const double k3_5 = i21 * g1_3 + i22 * g2_3 + i23 * g3_3;
    const double k3_6 = i31 * g1_3 + i32 * g2_3 + i33 * g3_3;
    const double k3_7 = b2_3 * w3_3 - b3_3 * w2_3;
    const double k3_8 = b3_3 * w1_3 - b1_3 * w3_3;
    const double k3_9 = b1_3 * w2_3 - b2_3 * w1_3;
    const double k3_10 = r2_3 * w3_3 - r3_3 * w2_3;
    const double k3_11 = r3_3 * w1_3 - r1_3 * w3_3;
    const double k3_12 = r1_3 * w2_3 - r2_3 * w1_3;
    /* stage 4 */
    const double q0_4 = q0 + dt * k3_0;
    const double q1_4 = q1 + dt * k3_1;
    const double q2_4 = q2 + dt * k3_2;
    const double q3_4 = q3 + dt * k3_3;
    const double w1_4 = w1 + dt * k3_4;
    const double w2_4 = w2 + dt * k3_5;
    const double w3_4 = w3 + dt * k3_6;
    const double b1_4 = b1 + dt * k3_7;
    const double b2_4 = b2 + dt * k3_8;
    const double b3_4 = b3 + dt * k3_9;
    const double r1_4 = r1 + dt * k3_10;
    const double r2_4 = r2 + dt * k3_11;
    const double r3_4 = r3 + dt * k3_12;
    const double s1_4 = j11 * r1_4 + j12 * r2_4 + j13 * r3_4;
    const double s2_4 = j21 * r1_4 + j22 * r2_4 + j23 * r3_4;
    const double s3_4 = j31 * r1_4 + j32 * r2_4 + j33 * r3_4;
    const double h1_4 = j11 * w1_4 + j12 * w2_4 + j13 * w3_4 + hx;
    const double h2_4 = j21 * w1_4 + j22 * w2_4 + j23 * w3_4 + hy;
    const double h3_4 = j31 * w1_4 + j32 * w2_4 + j33 * w3_4 + hz;
    const double g1_4 = tx + my * b3_4 - mz * b2_4 + g * (r2_4 * s3_4 - r3_4 * s2_4) - (w2_4 * h3_4 - w3_4 * h2_4);
    const double g2_4 = ty + mz * b1_4 - mx * b3_4 + g * (r3_4 * s1_4 - r1_4 * s3_4) - (w3_4 * h1_4 - w1_4 * h3_4);
    const double g3_4 = tz + mx * b2_4 - my * b1_4 + g * (r1_4 * s2_4 - r2_4 * s1_4) - (w1_4 * h2_4 - w2_4 * h1_4);
    const double k4_0 = 0.5 * (-q1_4 * w1_4 - q2_4 * w2_4 - q3_4 * w3_4);
    const double k4_1 = 0.5 * (q0_4 * w1_4 + q2_4 * w3_4 - q3_4 * w2_4);
    const double k4_2 = 0.5 * (q0_4 * w2_4 - q1_4 * w3_4 + q3_4 * w1_4);
    const double k4_3 = 0.5 * (q0_4 * w3_4 + q1_4 * w2_4 - q2_4 * w1_4);
    const double k4_4 = i11 * g1_4 + i12 * g2_4 + i13 * g3_4;
    const double k4_5 = i21 * g1_4 + i22 * g2_4 + i23 * g3_4;
    const double k4_6 = i31 * g1_4 + i32 * g2_4 + i33 * g3_4;
    /* combine and renormalise the quaternion */
    const double c = dt / 6.0;
    const double p0 = q0 + c * (k1_0 + 2.0 * (k2_0 + k3_0) + k4_0);
    const double p1 = q1 + c * (k1_1 + 2.0 * (k2_1 + k3_1) + k4_1);
    const double p2 = q2 + c * (k1_2 + 2.0 * (k2_2 + k3_2) + k4_2);
    const double p3 = q3 + c * (k1_3 + 2.0 * (k2_3 + k3_3) + k4_3);
    const double n = 1.0 / sqrt(p0 * p0 + p1 * p1 + p2 * p2 + p3 * p3);
    out[0] = p0 * n;
    out[1] = p1 * n;
    out[2] = p2 * n;
    out[3] = p3 * n;
    out[4] = w1 + c * (k1_4 + 2.0 * (k2_4 + k3_4) + k4_4);
    out[5] = w2 + c * (k1_5 + 2.0 * (k2_5 + k3_5) + k4_5);
    out[6] = w3 + c * (k1_6 + 2.0 * (k2_6 + k3_6) + k4_6);
}

/* CircularOrbit.position_N(t), the unit vector Plant._update_environment derives from it, and
 * DipoleField.b_N(t, r_N): out = r_N[3], r_hat_N[3], b_N[3]. */
static void fl_environment(const fl_env *e, double t, double *out)
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
    const double th = e->theta0 + e->earth_rate * t;
    const double c = cos(th), s = sin(th);
    const double dx = c * e->dx - s * e->dy;
    const double dy = s * e->dx + c * e->dy;
    const double dz = e->dz;
    const double r2 = x * x + y * y + z * z;
    const double r = sqrt(r2);
    const double inv_r3 = 1.0 / (r2 * r);
    const double k = 3.0 * (dx * x + dy * y + dz * z) / r2;
    out[0] = x;
    out[1] = y;
    out[2] = z;
    out[3] = x / rn;
    out[4] = y / rn;
    out[5] = z / rn;
    out[6] = (k * x - dx) * inv_r3;
    out[7] = (k * y - dy) * inv_r3;
    out[8] = (k * z - dz) * inv_r3;
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

/* Body(inertia9, inertia_inv9, wheel_momentum3): a rigid body's constants. */
typedef struct {
    PyObject_HEAD
    fl_body body;
    char has_env;
    fl_env env;
} KernelObject;

static PyMemberDef Kernel_members[] = {
    {"has_environment", T_BOOL, offsetof(KernelObject, has_env), READONLY,
     "whether environment() and step() are available (made with the environment constants)"},
    {NULL, 0, 0, 0, NULL},
};

static int Kernel_init(KernelObject *self, PyObject *args, PyObject *kwds)
{
    PyObject *j, *ji, *h, *env = Py_None;
    if (kwds != NULL && PyDict_GET_SIZE(kwds) != 0) {
        PyErr_SetString(PyExc_TypeError, "Kernel takes positional arguments only");
        return -1;
    }
    if (!PyArg_UnpackTuple(args, "Kernel", 3, 4, &j, &ji, &h, &env))
        return -1;
    if (read_floats(j, self->body.j, 9, "inertia") || read_floats(ji, self->body.ji, 9, "inertia_inv")
        || read_floats(h, self->body.h, 3, "wheel_momentum_B"))
        return -1;
    self->has_env = 0;
    if (env != Py_None) {
        double p[12];
        if (read_floats(env, p, 12, "environment"))
            return -1;
        self->env.a = p[0]; self->env.u0 = p[1]; self->env.u_rate = p[2]; self->env.raan0 = p[3];
        self->env.raan_rate = p[4]; self->env.ci = p[5]; self->env.si = p[6]; self->env.theta0 = p[7];
        self->env.earth_rate = p[8]; self->env.dx = p[9]; self->env.dy = p[10]; self->env.dz = p[11];
        self->has_env = 1;
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
        PyErr_SetString(PyExc_ValueError, "this kernel was made without an environment (circular orbit + dipole)");
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
    fl_environment(&self->env, t, e);
    return env_tuples(e);
}

/* step(state, dt, m_B, b_N, gg, r_hat_N, t1) -> (state1, r_N, r_hat_N, b_N): step_env, then the
 * environment at the step's end t1 (what Plant.step_ns does with the two). */
static PyObject *Kernel_step(KernelObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    static const double tau[3] = {0.0, 0.0, 0.0};
    double st[7], m[3], b[3], r[3], out[7], e[9], dt, g, t1;
    if (check_nargs(nargs, 7, 7, "step") || need_env(self)
        || read_floats(args[0], st, 7, "state") || read_float(args[1], &dt)
        || read_floats(args[2], m, 3, "m_B") || read_floats(args[3], b, 3, "b_N") || read_float(args[4], &g)
        || read_floats(args[5], r, 3, "r_hat_N") || read_float(args[6], &t1))
        return NULL;
    fl_step_env(&self->body, st, dt, m, b, g, r, tau, out);
    fl_environment(&self->env, t1, e);
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

static PyMethodDef Kernel_methods[] = {
    {"step_env", (PyCFunction)(void (*)(void))Kernel_step_env, METH_FASTCALL,
     "step_env(state, dt, m_B, b_N, gg, r_hat_N[, torque_B]) -> state: RigidBody.step_env"},
    {"environment", (PyCFunction)(void (*)(void))Kernel_environment, METH_FASTCALL,
     "environment(t) -> (r_N, r_hat_N, b_N): circular orbit and centred dipole at t seconds"},
    {"step", (PyCFunction)(void (*)(void))Kernel_step, METH_FASTCALL,
     "step(state, dt, m_B, b_N, gg, r_hat_N, t1) -> (state1, r_N, r_hat_N, b_N)"},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject KernelType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "detumble.sim._plant_kernel.Kernel",
    .tp_basicsize = sizeof(KernelObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Kernel(inertia9, inertia_inv9, wheel_momentum_B[, environment12]): one body's compiled step",
    .tp_methods = Kernel_methods,
    .tp_members = Kernel_members,
    .tp_init = (initproc)Kernel_init,
    .tp_new = PyType_GenericNew,
};

static struct PyModuleDef kernel_module = {
    PyModuleDef_HEAD_INIT, "_plant_kernel", "Compiled plant kernel (see detumble.sim.plant_kernel).", -1,
    NULL, NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__plant_kernel(void)
{
    if (PyType_Ready(&KernelType) < 0)
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

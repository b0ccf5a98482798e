// Water surfaces evaluated on the device: flat, Gerstner (the same Newton inversion as
// btGerstnerWaterSurface::solve, cold start), and a bilinear height grid (btGridWaterSurface; also used for
// a flat-sampled FFT ocean). The host packs the parameters in btOpenClBuoyancyBackend.cpp (packWater).
//
// wp layout (bb_real):
//   flat:     [0] level h, [1] current x, [2] current z
//   Gerstner: [0] mean level h, [1] wave count m, [2] residual tolerance², [3] iteration limit,
//             then per wave (BB_GERSTNER_STRIDE): A, k, ω, d_x, d_z, Q·A, φ   (θ = k d·x₀ − ω t + φ)
//   grid:     [0] nx, [1] nz, [2] spacing, [3] origin x, [4] origin z, [5] periodic (0/1), [6] has velocities;
//             `grid` holds nx·nz heights (index j·nx + i), then vx, vy, vz when [6] is 1

#define BB_WATER_FLAT 0
#define BB_WATER_GERSTNER 1
#define BB_WATER_GRID 2
#define BB_GERSTNER_HEADER 8
#define BB_GERSTNER_STRIDE 8

// Newton inversion of x₀ − Σ Q A d sin θ(x₀) = (x, z) (btGerstnerWaterSurface.h, restPosition): Jacobian
// I − Σ Q A k cos θ d dᵀ; a step that does not reduce the residual is replaced by the fixed-point step.
// Returns Σ A cos θ at the solution; with wantVel, vel = orbital velocity at yRel = y − h, scaled by
// e^{k min(0, yRel)} (linear wave theory).
// g: in the start guess of the rest position (x₀, z₀), out the solution (the warm start of the next query,
// as btGerstnerWaterSurface::heightsCached keeps x − x₀ per point).
static bb_real bb_gerstner_solve(__global const bb_real* wp, bb_real x, bb_real z, bb_real t, bb_real yRel,
                                 int wantVel, bb_real* vel, bb_real* g) {
    const int m = (int)wp[1];
    const bb_real tol2 = wp[2];
    const int maxIt = (int)wp[3];
    const bb_real depth = yRel < 0 ? yRel : (bb_real)0;
    bb_real x0 = g[0], z0 = g[1], px = x0, pz = z0, prx = 0, prz = 0, pr2 = (bb_real)INFINITY, ySum = 0;
    for (int it = 0;; ++it) {
        bb_real rx = x0 - x, rz = z0 - z, jxx = 1, jxz = 0, jzz = 1, ys = 0, vx = 0, vy = 0, vz = 0;
        for (int i = 0; i < m; ++i) {
            __global const bb_real* w = wp + BB_GERSTNER_HEADER + BB_GERSTNER_STRIDE * i;
            const bb_real a = w[0], k = w[1], om = w[2], dx = w[3], dz = w[4], qa = w[5], ph = w[6];
            const bb_real th = k * dx * x0 + k * dz * z0 + (ph - om * t);
            bb_real c;
            const bb_real s = sincos(th, &c);
            rx -= qa * dx * s;
            rz -= qa * dz * s;
            jxx -= qa * k * dx * dx * c;
            jxz -= qa * k * dx * dz * c;
            jzz -= qa * k * dz * dz * c;
            ys += a * c;
            if (wantVel) {
                const bb_real e = depth < 0 ? exp(k * depth) : (bb_real)1;
                vx += qa * om * dx * c * e;
                vz += qa * om * dz * c * e;
                vy += a * om * s * e;
            }
        }
        ySum = ys;
        if (wantVel) {
            vel[0] = vx;
            vel[1] = vy;
            vel[2] = vz;
        }
        const bb_real r2 = rx * rx + rz * rz;
        if (r2 <= tol2 || it >= maxIt) break;
        if (!(r2 < pr2)) {
            x0 = px - prx;
            z0 = pz - prz;
            pr2 = (bb_real)INFINITY;
            continue;
        }
        px = x0;
        pz = z0;
        prx = rx;
        prz = rz;
        pr2 = r2;
        const bb_real inv = (bb_real)1 / (jxx * jzz - jxz * jxz);
        x0 -= (jzz * rx - jxz * rz) * inv;
        z0 -= (jxx * rz - jxz * rx) * inv;
    }
    g[0] = x0;
    g[1] = z0;
    return ySum;
}

static int bb_grid_wrap(long i, int n, int periodic) {
    if (periodic) {
        long r = i % n;
        return (int)(r < 0 ? r + n : r);
    }
    return (int)(i < 0 ? 0 : (i > n - 1 ? n - 1 : i));
}

// Bilinear lookup of field `f` (nx·nz values) at (x, z), as btGridWaterSurface::sample.
static bb_real bb_grid_sample(__global const bb_real* wp, __global const bb_real* f, bb_real x, bb_real z) {
    const int nx = (int)wp[0], nz = (int)wp[1], periodic = wp[5] != 0;
    bb_real u = (x - wp[3]) / wp[2], v = (z - wp[4]) / wp[2];
    if (!periodic) {
        u = u < 0 ? (bb_real)0 : (u > (bb_real)(nx - 1) ? (bb_real)(nx - 1) : u);
        v = v < 0 ? (bb_real)0 : (v > (bb_real)(nz - 1) ? (bb_real)(nz - 1) : v);
    }
    const bb_real fu = floor(u), fv = floor(v);
    const bb_real a = u - fu, b = v - fv;
    const long iu = (long)fu, iv = (long)fv;
    const int i0 = bb_grid_wrap(iu, nx, periodic), i1 = bb_grid_wrap(iu + 1, nx, periodic);
    const int j0 = bb_grid_wrap(iv, nz, periodic), j1 = bb_grid_wrap(iv + 1, nz, periodic);
    const bb_real h00 = f[j0 * nx + i0], h10 = f[j0 * nx + i1], h01 = f[j1 * nx + i0], h11 = f[j1 * nx + i1];
    return (1 - b) * ((1 - a) * h00 + a * h10) + b * ((1 - a) * h01 + a * h11);
}

// Water height f(x, z, t), m. g: Gerstner rest-position guess in, solution out (see bb_gerstner_solve).
static bb_real bb_water_height(int type, __global const bb_real* wp, __global const bb_real* grid, bb_real x,
                               bb_real z, bb_real t, bb_real* g) {
    if (type == BB_WATER_GERSTNER) return wp[0] + bb_gerstner_solve(wp, x, z, t, 0, 0, 0, g);
    if (type == BB_WATER_GRID) return bb_grid_sample(wp, grid, x, z);
    return wp[0];
}

// Water velocity u(x, y, z, t), m/s. g as in bb_water_height (after it, one evaluation of the waves).
static void bb_water_velocity(int type, __global const bb_real* wp, __global const bb_real* grid, bb_real x,
                              bb_real y, bb_real z, bb_real t, bb_real* u, bb_real* g) {
    u[0] = 0;
    u[1] = 0;
    u[2] = 0;
    if (type == BB_WATER_GERSTNER) {
        bb_gerstner_solve(wp, x, z, t, y - wp[0], 1, u, g);
    } else if (type == BB_WATER_GRID) {
        if (wp[6] != 0) {
            const int nn = (int)wp[0] * (int)wp[1];
            u[0] = bb_grid_sample(wp, grid + nn, x, z);
            u[1] = bb_grid_sample(wp, grid + 2 * nn, x, z);
            u[2] = bb_grid_sample(wp, grid + 3 * nn, x, z);
        }
    } else {
        u[0] = wp[1];
        u[2] = wp[2];
    }
}

// Warm start of the Gerstner inversion per (body, sample): state holds x − x₀ and z − z₀ of the last query.
static void bb_guess_load(__global const bb_real* st, bb_real x, bb_real z, bb_real* g) {
    g[0] = x - st[0];
    g[1] = z - st[1];
}
static void bb_guess_store(__global bb_real* st, bb_real x, bb_real z, const bb_real* g) {
    const bb_real dx = x - g[0], dz = z - g[1];
    st[0] = isfinite(dx) ? dx : (bb_real)0;  // one bad point never poisons the next warm start
    st[1] = isfinite(dz) ? dz : (bb_real)0;
}

// Per-sample work of the OpenCL backend: every body of a world in one launch per pass.
// The formulas are those of plugin/BulletBuoyancy/geometry/SampleFormulas.h (prepended to this program), shared with the
// CPU path. Host side: plugin/BulletBuoyancy/bullet/btOpenClBuoyancyBackend.cpp.
//
// samples: BB_SAMPLE_STRIDE reals per sample, every mesh of the world in one buffer:
//          px py pz ax ay az area | cxx cxy cxz cyy cyz czz, velocity probe x y z (drag clusters only)
// bodies:  BB_BODY_STRIDE reals per body: R (9, row-major, mesh → world), t − c (3), c = COM (3),
//          v (3), ω (3), ½ρC_d, ½ρC_f, ρb  (drag pass only)
// tiles:   int4 (body, first sample, sample count, first state): one work-group per tile; a body's tiles are
//          consecutive; state (2 reals per body-sample, the Gerstner warm start) of sample i is at
//          first state + (i − first sample)
// partials: terms per tile (BB_HYDRO_TERMS or BB_DRAG_TERMS), summed per body by bb_reduce_bodies

#define BB_SAMPLE_STRIDE 16
#define BB_BODY_STRIDE 32

static void bb_load_body(__global const bb_real* B, bb_real* R, bb_real* t, bb_real* c) {
    for (int k = 0; k < 9; ++k) R[k] = B[k];
    for (int k = 0; k < 3; ++k) {
        t[k] = B[9 + k];
        c[k] = B[12 + k];
    }
}

// Work-group tree reduction of `nterms` private sums into partials[group·nterms ...]; local size a power of 2.
static void bb_group_reduce(const bb_real* part, int nterms, __local bb_real* scratch, __global bb_real* partials) {
    const int lid = get_local_id(0), L = get_local_size(0);
    for (int k = 0; k < nterms; ++k) scratch[lid * nterms + k] = part[k];
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int off = L / 2; off > 0; off >>= 1) {
        if (lid < off)
            for (int k = 0; k < nterms; ++k) scratch[lid * nterms + k] += scratch[(lid + off) * nterms + k];
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (lid == 0)
        for (int k = 0; k < nterms; ++k) partials[get_group_id(0) * nterms + k] = scratch[k];
}

// Hydrostatics (design.md 2.2–2.3): transform, water height, wetted sums about the COM.
__kernel void bb_hydro_tiles(__global const bb_real* samples, __global const bb_real* bodies,
                             __global const int4* tiles, int waterType, __global const bb_real* wp,
                             __global const bb_real* grid, bb_real time, __global bb_real* partials,
                             __local bb_real* scratch, __global bb_real* state) {
    const int4 tl = tiles[get_group_id(0)];
    bb_real R[9], t[3], c[3];
    bb_load_body(bodies + tl.x * BB_BODY_STRIDE, R, t, c);
    bb_real part[BB_HYDRO_TERMS];
    for (int k = 0; k < BB_HYDRO_TERMS; ++k) part[k] = 0;
    const int end = tl.y + tl.z;
    for (int i = tl.y + get_local_id(0); i < end; i += get_local_size(0)) {
        __global const bb_real* S = samples + (long)i * BB_SAMPLE_STRIDE;
        bb_real p[3], A[3];
        bb_transform_sample(R, t, S[0], S[1], S[2], S[3], S[4], S[5], p, A);
        const bb_real x = p[0] + c[0], z = p[2] + c[2];
        __global bb_real* st = state + 2 * ((long)tl.w + (i - tl.y));
        bb_real g[2];
        bb_guess_load(st, x, z, g);
        const bb_real fr = bb_water_height(waterType, wp, grid, x, z, time, g) - c[1];
        bb_guess_store(st, x, z, g);
        bb_hydro_accumulate(p[0], p[1], p[2], fr, bb_wet_depth(p[1], fr), A[0], A[1], A[2], S[6], part);
    }
    bb_group_reduce(part, BB_HYDRO_TERMS, scratch, partials);
}

// Drag (design.md 2.6) on the drag clusters: transform, wet fraction over the cluster's vertical half
// extent, water velocity, drag sums about the COM.
__kernel void bb_drag_tiles(__global const bb_real* samples, __global const bb_real* bodies,
                            __global const int4* tiles, int waterType, __global const bb_real* wp,
                            __global const bb_real* grid, bb_real time, __global bb_real* partials,
                            __local bb_real* scratch, __global bb_real* state) {
    const int4 tl = tiles[get_group_id(0)];
    __global const bb_real* B = bodies + tl.x * BB_BODY_STRIDE;
    bb_real R[9], t[3], c[3], v[3], w[3];
    bb_load_body(B, R, t, c);
    for (int k = 0; k < 3; ++k) {
        v[k] = B[15 + k];
        w[k] = B[18 + k];
    }
    const bb_real kd = B[21], kf = B[22], kl = B[23];
    bb_real part[BB_DRAG_TERMS];
    for (int k = 0; k < BB_DRAG_TERMS; ++k) part[k] = 0;
    const int end = tl.y + tl.z;
    for (int i = tl.y + get_local_id(0); i < end; i += get_local_size(0)) {
        __global const bb_real* S = samples + (long)i * BB_SAMPLE_STRIDE;
        bb_real p[3], A[3], C[6];
        bb_transform_sample(R, t, S[0], S[1], S[2], S[3], S[4], S[5], p, A);
        for (int k = 0; k < 6; ++k) C[k] = S[7 + k];
        const bb_real x = p[0] + c[0], y = p[1] + c[1], z = p[2] + c[2];
        __global bb_real* st = state + 2 * ((long)tl.w + (i - tl.y));
        bb_real g[2];
        bb_guess_load(st, x, z, g);
        const bb_real depth = bb_water_height(waterType, wp, grid, x, z, time, g) - y;
        const bb_real wet = bb_drag_wet_ramp(bb_cluster_half_extent(R, C), depth);
        if (!(wet > 0)) {
            bb_guess_store(st, x, z, g);
            continue;
        }
        bb_guess_store(st, x, z, g);
        // Water velocity at the cluster's velocity probe (integrals/DragClusters.h; the cluster itself when it has
        // its own), warm-started from the cluster's rest position.
        bb_real q[3], qa[3], u[3];
        bb_transform_sample(R, t, S[13], S[14], S[15], 0, 0, 0, q, qa);
        const bb_real qx = q[0] + c[0], qz = q[2] + c[2];
        g[0] += qx - x;
        g[1] += qz - z;
        bb_water_velocity(waterType, wp, grid, qx, q[1] + c[1], qz, time, u, g);
        bb_drag_cluster_accumulate(R, C, p, v, w, u, A[0], A[1], A[2], S[6], wet, kd, kf, kl, part);
    }
    bb_group_reduce(part, BB_DRAG_TERMS, scratch, partials);
}

// Per-body sums of the tile partials (in tile order, so the result does not depend on scheduling).
// bodyTiles: int2 (first tile, end tile) per body; out: nterms per body.
__kernel void bb_reduce_bodies(__global const bb_real* partials, __global const int2* bodyTiles, int nterms,
                               int nbodies, __global bb_real* out) {
    const int b = get_global_id(0);
    if (b >= nbodies) return;
    const int2 r = bodyTiles[b];
    for (int k = 0; k < nterms; ++k) {
        bb_real s = 0;
        for (int i = r.x; i < r.y; ++i) s += partials[i * nterms + k];
        out[b * nterms + k] = s;
    }
}

// bench/peer_embree.cpp -- Embree 3 in make bench's peer rows (bench/peers.h says what each mode
// prints), where it is installed (Debian's libembree-dev; bench/peers.sh builds this as
// build/peer_embree). One thread, its default build quality and ISA, rtcIntersect1; its robust
// mode (RTC_SCENE_FLAG_ROBUST) as a second column of the crack table (`cracks-robust`). Its
// bytes are what it allocates, counted by its own memory monitor
// (rtcSetDeviceMemoryMonitorFunction): the vertex and index buffers it was given, and the BVH.
#include "peers.h"

#include <embree3/rtcore.h>

#include <atomic>

static std::atomic<long long> gBytes(0); // what Embree holds now (its monitor's running sum)

static bool Monitor(void *, ssize_t bytes, bool) {
    gBytes += bytes;
    return true;
}

static RTCScene Build(RTCDevice device, const std::vector<float> &v, const std::vector<unsigned> &f,
                      bool robust) {
    RTCScene scene = rtcNewScene(device);
    if (robust)
        rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry mesh = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vertices = (float *)rtcSetNewGeometryBuffer(
        mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), v.size() / 3);
    unsigned *faces = (unsigned *)rtcSetNewGeometryBuffer(
        mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), f.size() / 3);
    memcpy(vertices, v.data(), v.size() * sizeof(float));
    memcpy(faces, f.data(), f.size() * sizeof(unsigned));
    rtcCommitGeometry(mesh);
    rtcAttachGeometry(scene, mesh);
    rtcReleaseGeometry(mesh);
    rtcCommitScene(scene);
    return scene;
}

static bool Trace(RTCScene scene, const float o[3], const float d[3], double *t) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
    rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
    rh.ray.tnear = 0, rh.ray.tfar = 1e30f, rh.ray.time = 0;
    rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    *t = rh.ray.tfar;
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

static void Time(RTCDevice device, const std::vector<float> &v, const std::vector<unsigned> &f,
                 int rounds) {
    auto start = std::chrono::steady_clock::now();
    RTCScene scene = Build(device, v, f, false);
    printf("%.3f\n", peers::Ms(start));
    long hits = peers::TimeEyeRays(
        rounds, [&](const float *o, const float *d, double *t) { return Trace(scene, o, d, t); });
    printf("hits %ld\nbytes %lld\n", hits, (long long)gBytes);
    rtcReleaseScene(scene);
}

static void Cracks(RTCDevice device, const std::vector<float> &v, const std::vector<unsigned> &f,
                   bool robust) {
    RTCScene scene = Build(device, v, f, robust);
    peers::PrintCracks(
        v, f, [&](const float *o, const float *d, double *t) { return Trace(scene, o, d, t); });
    rtcReleaseScene(scene);
}

int main(int argc, char **argv) {
    bool robust = argc == 3 && !strcmp(argv[1], "cracks-robust");
    char cracks[] = "cracks";
    if (robust)
        argv[1] = cracks;
    int rounds;
    int mode = peers::Mode(argc, argv, "peer_embree", &rounds);
    std::vector<float> v;
    std::vector<unsigned> f;
    if (mode < 0 || !peers::ReadObj(argv[2], &v, &f))
        return 2;
    RTCDevice device = rtcNewDevice("threads=1");
    rtcSetDeviceMemoryMonitorFunction(device, Monitor, nullptr);
    if (mode == 0)
        Time(device, v, f, rounds);
    else
        Cracks(device, v, f, robust);
    rtcReleaseDevice(device);
    return 0;
}

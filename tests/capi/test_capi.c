/* The C API (ellicast.h) as a C99 program uses it: encode a model, walk the recording's packets,
 * give them to a receiver as datagrams (all, some, damaged ones), ask for progress and snapshots
 * (GLB bytes checked by the Khronos glTF-Validator when it is installed, meshes as arrays), and every
 * bad call answered with a status and a message naming what was wrong.
 *
 * Usage: test_capi SOURCE_DIR SHARED_SAMPLES_DIR SCRATCH_DIR
 * Prints one line a check and "N passed, N failed" at the end; exits 1 when a check failed.
 * A check that needs ../shared/samples (or the validator) is skipped with a message when it is absent. */
#define _POSIX_C_SOURCE 200809L
#include <ellicast.h>

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int passed, failed;
static const char *source_dir, *samples_dir, *scratch_dir;

#define CHECK(cond, ...)                                   \
    do {                                                   \
        if (cond) {                                        \
            ++passed;                                      \
        } else {                                           \
            ++failed;                                      \
            printf("FAILED %s:%d: %s: ", __FILE__, __LINE__, #cond); \
            printf(__VA_ARGS__);                           \
            printf(" (last error: %s)\n", ellicast_last_error()); \
        }                                                  \
    } while (0)

static int contains(const char* text, const char* part) { return text && strstr(text, part) != NULL; }

static int file_exists(const char* path) {
    struct stat st;
    return stat(path, &st) == 0;
}

static unsigned char* read_whole(const char* path, size_t* size) {
    FILE* f = fopen(path, "rb");
    unsigned char* data;
    long n;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    data = (unsigned char*)malloc(n > 0 ? (size_t)n : 1);
    if (data && n > 0 && fread(data, 1, (size_t)n, f) != (size_t)n) {
        free(data);
        data = NULL;
    }
    fclose(f);
    *size = (size_t)n;
    return data;
}

static int write_whole(const char* path, const uint8_t* data, size_t size) {
    FILE* f = fopen(path, "wb");
    int ok;
    if (!f) return 0;
    ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

/* Runs the Khronos validator on `path`: 1 valid, 0 invalid, -1 not installed (skipped). */
static int validate_glb(const char* path) {
    char modules[4096], command[8192], line[4096];
    FILE* pipe;
    int valid = 0;
    snprintf(modules, sizeof modules, "%s/.cache/node/node_modules/gltf-validator", source_dir);
    if (!file_exists(modules) || system("command -v node > /dev/null 2>&1") != 0) {
        printf("skipped: the glTF-Validator is not installed (run scripts/setup.sh): %s not validated\n", path);
        return -1;
    }
    snprintf(command, sizeof command, "NODE_PATH='%s/.cache/node/node_modules' node '%s/tests/gltf_validate.js' '%s' 2>&1",
             source_dir, source_dir, path);
    pipe = popen(command, "r");
    if (!pipe) return 0;
    while (fgets(line, sizeof line, pipe)) {
        if (contains(line, "\"numErrors\":0")) valid = 1;
        else printf("validator: %s", line);
    }
    pclose(pipe);
    return valid;
}

/* Packet type: byte 6 of the 20-byte header (spec 3.1). */
static int packet_type(const uint8_t* packet) { return packet[6]; }

static void check_versions(void) {
    int major = 0, minor = 0;
    CHECK(strcmp(ellicast_version(), "1.0.0") == 0, "version %s", ellicast_version());
    ellicast_format_version(&major, &minor);
    CHECK(major == 1 && minor == 14, "format %d.%d", major, minor);
    CHECK(strcmp(ellicast_status_name(ELLICAST_ERROR_INPUT), "ELLICAST_ERROR_INPUT") == 0, "status name");
    CHECK(ellicast_last_error() != NULL, "last error never NULL");
}

static void check_bad_calls(void) {
    ellicast_receiver* r = NULL;
    ellicast_receiver_options ro;
    ellicast_encode_options eo;
    ellicast_buffer out = {NULL, 0};
    ellicast_progress p;
    ellicast_object_progress op;
    const uint8_t* packet;
    size_t packet_size, offset = 0;
    char path[4096];

    CHECK(ellicast_receiver_create(NULL, NULL) == ELLICAST_ERROR_ARGUMENT && contains(ellicast_last_error(), "out is NULL"),
          "create without out");
    memset(&ro, 0, sizeof ro);
    CHECK(ellicast_receiver_create(&ro, &r) == ELLICAST_ERROR_ARGUMENT && contains(ellicast_last_error(), "struct_size") && !r,
          "options not initialized");
    ellicast_receiver_options_init(&ro);
    ro.grid_resolution = 100000;
    CHECK(ellicast_receiver_create(&ro, &r) == ELLICAST_ERROR_ARGUMENT && contains(ellicast_last_error(), "grid_resolution"),
          "absurd grid");
    ellicast_receiver_options_init(&ro);
    ro.public_key_path = "/nonexistent/key.pub";
    CHECK(ellicast_receiver_create(&ro, &r) == ELLICAST_ERROR_INPUT && contains(ellicast_last_error(), "public_key_path"),
          "missing key file");

    CHECK(ellicast_receiver_create(NULL, &r) == ELLICAST_OK && r, "create with defaults");
    CHECK(strcmp(ellicast_last_error(), "") == 0, "a call that succeeds clears the message");
    CHECK(ellicast_receiver_progress(r, &p) == ELLICAST_OK && p.objects == 0 && p.complete == 0 && p.datagrams == 0,
          "progress of an empty receiver");
    CHECK(ellicast_receiver_snapshot_glb(r, &out) == ELLICAST_ERROR_NOT_READY && contains(ellicast_last_error(), "STREAM_INFO") &&
              out.data == NULL,
          "nothing to show before the stream info");
    CHECK(ellicast_receiver_object_progress(r, 0, &op) == ELLICAST_ERROR_ARGUMENT && contains(ellicast_last_error(), "object 0"),
          "object out of range");
    CHECK(ellicast_receiver_take_datagram(r, "hello", 5) == ELLICAST_ERROR_REJECTED && contains(ellicast_last_error(), "dropped"),
          "someone else's datagram");
    CHECK(ellicast_receiver_take_datagram(r, NULL, 4) == ELLICAST_ERROR_ARGUMENT, "NULL datagram");
    CHECK(ellicast_receiver_take_recording(r, "not a recording at all", 22) == ELLICAST_ERROR_INPUT &&
              contains(ellicast_last_error(), "not an ellicast recording"),
          "garbage recording");
    CHECK(ellicast_receiver_take_file(r, "/nonexistent/stream.ellc") == ELLICAST_ERROR_IO &&
              contains(ellicast_last_error(), "/nonexistent/stream.ellc"),
          "missing recording names the file");
    CHECK(ellicast_receiver_progress(r, &p) == ELLICAST_OK && p.datagrams == 1 && p.rejected == 1, "the dropped datagram counted");
    ellicast_receiver_destroy(r);
    ellicast_receiver_destroy(NULL);

    ellicast_encode_options_init(&eo);
    eo.packet_size = 10;
    snprintf(path, sizeof path, "%s/samples/trefoil.obj", source_dir);
    CHECK(ellicast_encode_file(path, &eo, &out) == ELLICAST_ERROR_ARGUMENT && contains(ellicast_last_error(), "packet") && !out.data,
          "absurd packet size");
    ellicast_encode_options_init(&eo);
    eo.repair_ratio = 99;
    CHECK(ellicast_encode_file(path, &eo, &out) == ELLICAST_ERROR_ARGUMENT && contains(ellicast_last_error(), "repair"),
          "absurd repair ratio");
    eo.struct_size = 8;
    CHECK(ellicast_encode_file(path, &eo, &out) == ELLICAST_ERROR_ARGUMENT && contains(ellicast_last_error(), "struct_size"),
          "encode options not initialized");
    /* A caller built against 1.0 passes the struct as it ended there: accepted, with the default budget
     * (its sample_budget field is not read, whatever the memory after the struct holds). */
    ellicast_encode_options_init(&eo);
    eo.sample_budget = -1000; /* absurd: refused when read, ignored when the caller's struct ends before it */
    eo.struct_size = offsetof(ellicast_encode_options, sample_budget);
    CHECK(ellicast_encode_file(path, &eo, &out) == ELLICAST_OK && out.data, "a 1.0-sized encode options struct");
    ellicast_buffer_free(&out);
    eo.struct_size = sizeof eo;
    CHECK(ellicast_encode_file(path, &eo, &out) == ELLICAST_ERROR_ARGUMENT && contains(ellicast_last_error(), "sample budget"),
          "absurd sample budget");
    CHECK(ellicast_encode_file("/nonexistent/model.obj", NULL, &out) == ELLICAST_ERROR_INPUT &&
              contains(ellicast_last_error(), "/nonexistent/model.obj"),
          "missing model names the file");
    CHECK(ellicast_encode_memory("solid x\n", 8, "fbx", NULL, &out) == ELLICAST_ERROR_ARGUMENT &&
              contains(ellicast_last_error(), "\"fbx\""),
          "unknown model type");
    CHECK(ellicast_encode_memory("v 0 0 0\nf 1 2 3\n", 16, "obj", NULL, &out) == ELLICAST_ERROR_INPUT &&
              contains(ellicast_last_error(), "in memory") && !contains(ellicast_last_error(), "/tmp/"),
          "a broken model in memory: the message names the buffer, not a temporary file");
    CHECK(ellicast_encode_file(NULL, NULL, &out) == ELLICAST_ERROR_ARGUMENT, "NULL path");
    CHECK(ellicast_recording_next_packet("xx", 2, &offset, &packet, &packet_size) == ELLICAST_ERROR_INPUT, "walking garbage");
    ellicast_buffer_free(&out);
    ellicast_buffer_free(NULL);
}

static void count_progress(const char* stage, double fraction, void* user) {
    (void)stage;
    (void)fraction;
    ++*(int*)user;
}

/* Encodes the bundled trefoil, receives it whole, with loss, and with damage. */
static void check_round_trip(void) {
    char path[4096], glb_path[4096];
    ellicast_encode_options eo;
    ellicast_buffer stream = {NULL, 0}, glb = {NULL, 0};
    ellicast_receiver* r = NULL;
    ellicast_progress p;
    ellicast_object_progress op;
    ellicast_snapshot* s = NULL;
    ellicast_mesh m;
    size_t offset = 0, packet_size = 0, packets = 0, taken = 0, i;
    const uint8_t* packet = NULL;
    int calls = 0, bad = 0, damaged_sent = 0;
    uint8_t damaged[2048];

    snprintf(path, sizeof path, "%s/samples/trefoil.obj", source_dir);
    ellicast_encode_options_init(&eo);
    eo.progress = count_progress;
    eo.progress_user = &calls;
    CHECK(ellicast_encode_file(path, &eo, &stream) == ELLICAST_OK && stream.size > 1000, "encode the trefoil");
    if (!stream.data) return;
    CHECK(calls > 0, "progress reported while encoding");
    CHECK(stream.data[0] == 0x89 && stream.data[1] == 'E' && stream.data[2] == 'L' && stream.data[3] == 'C', "a container file");

    /* Every packet as a datagram. */
    CHECK(ellicast_receiver_create(NULL, &r) == ELLICAST_OK, "receiver");
    for (;;) {
        if (ellicast_recording_next_packet(stream.data, stream.size, &offset, &packet, &packet_size) != ELLICAST_OK) {
            bad = 1;
            break;
        }
        if (!packet) break;
        ++packets;
        if (ellicast_receiver_take_datagram(r, packet, packet_size) != ELLICAST_OK) bad = 1;
    }
    CHECK(!bad && packets > 10 && offset == stream.size, "every packet walked and taken (%zu)", packets);
    CHECK(ellicast_receiver_progress(r, &p) == ELLICAST_OK, "progress");
    CHECK(p.complete && p.base_complete && p.objects == 1 && p.exact_objects == 1, "complete and exact");
    CHECK(p.points_received == p.points_declared && p.points_declared > 1000, "every point (%llu of %llu)",
          (unsigned long long)p.points_received, (unsigned long long)p.points_declared);
    CHECK(p.accepted + p.duplicates == packets && p.rejected == 0, "counters");
    CHECK(ellicast_receiver_object_progress(r, 0, &op) == ELLICAST_OK && op.arrived && op.exact && op.has_exact_layer &&
              !op.point_set && op.ellipsoids_received == op.ellipsoids_declared && op.ellipsoids_declared > 0,
          "object 0");
    CHECK(ellicast_receiver_snapshot(r, &s) == ELLICAST_OK && s, "snapshot");
    if (s) {
        CHECK(ellicast_snapshot_mesh_count(s) == 1, "one mesh");
        CHECK(ellicast_snapshot_mesh(s, 0, &m) == ELLICAST_OK && m.vertex_count > 1000 && m.triangle_count > 2000 && m.positions &&
                  m.indices,
              "the mesh as arrays (%zu vertices, %zu triangles)", m.vertex_count, m.triangle_count);
        for (i = 0, bad = 0; i < 3 * m.triangle_count; ++i) bad |= m.indices[i] >= m.vertex_count;
        CHECK(!bad, "every index names a vertex");
        CHECK(ellicast_snapshot_mesh(s, 1, &m) == ELLICAST_ERROR_ARGUMENT, "mesh out of range");
        CHECK(ellicast_snapshot_glb(s, &glb) == ELLICAST_OK && glb.size > 1000 && memcmp(glb.data, "glTF", 4) == 0 &&
                  glb.data[4] == 2,
              "GLB bytes");
        snprintf(glb_path, sizeof glb_path, "%s/trefoil-complete.glb", scratch_dir);
        CHECK(write_whole(glb_path, glb.data, glb.size), "write %s", glb_path);
        CHECK(validate_glb(glb_path) != 0, "the complete GLB is valid glTF");
        ellicast_buffer_free(&glb);
        CHECK(glb.data == NULL && glb.size == 0, "buffer freed");
        ellicast_snapshot_destroy(s);
    }
    ellicast_receiver_destroy(r);

    /* Half the detail lost (every other point, normal or exact-layer packet, and every repair packet), and one
     * damaged datagram: a picture all the same, not complete, the damage counted. */
    CHECK(ellicast_receiver_create(NULL, &r) == ELLICAST_OK, "receiver");
    offset = 0;
    for (i = 0; ellicast_recording_next_packet(stream.data, stream.size, &offset, &packet, &packet_size) == ELLICAST_OK && packet; ++i) {
        const int type = packet_type(packet);
        const int base = type == 0x01 || type == 0x02 || type == 0x0A; /* stream info, ellipsoids, point map */
        if (type == 0x04 || type == 0x06) continue;  /* no repair packets: the loss stays */
        if (!base && i % 2 == 1) continue;           /* every other detail packet (a carousel repeats the base) */
        if (packet_size <= sizeof damaged && (type == 0x03 || type == 0x09) && !damaged_sent) {
            memcpy(damaged, packet, packet_size);
            damaged[packet_size / 2] ^= 0x10;
            CHECK(ellicast_receiver_take_datagram(r, damaged, packet_size) == ELLICAST_ERROR_REJECTED &&
                      contains(ellicast_last_error(), "bad CRC-32C"),
                  "a damaged packet is dropped, naming its checksum");
            damaged_sent = 1;
        }
        taken += ellicast_receiver_take_datagram(r, packet, packet_size) == ELLICAST_OK;
    }
    CHECK(ellicast_receiver_progress(r, &p) == ELLICAST_OK && !p.complete && p.exact_objects == 0 && p.rejected == 1 &&
              p.points_received > 0 && p.points_received < p.points_declared,
          "half lost: not complete (%llu of %llu points, %zu taken)", (unsigned long long)p.points_received,
          (unsigned long long)p.points_declared, taken);
    CHECK(ellicast_receiver_snapshot_glb(r, &glb) == ELLICAST_OK && glb.size > 1000, "a picture after half the packets");
    snprintf(glb_path, sizeof glb_path, "%s/trefoil-half.glb", scratch_dir);
    CHECK(glb.data && write_whole(glb_path, glb.data, glb.size), "write %s", glb_path);
    if (glb.data) CHECK(validate_glb(glb_path) != 0, "the lossy GLB is valid glTF");
    ellicast_buffer_free(&glb);

    /* The rest of the recording completes it (loss only lowers the quality until packets come round). */
    CHECK(ellicast_receiver_take_recording(r, stream.data, stream.size) == ELLICAST_OK, "the whole recording");
    CHECK(ellicast_receiver_progress(r, &p) == ELLICAST_OK && p.complete && p.exact_objects == 1, "complete after the rest");
    ellicast_receiver_destroy(r);

    /* A recording with damage in the middle still gives its intact packets. */
    stream.data[stream.size / 2] ^= 0xFF;
    CHECK(ellicast_receiver_create(NULL, &r) == ELLICAST_OK, "receiver");
    CHECK(ellicast_receiver_take_recording(r, stream.data, stream.size) == ELLICAST_OK, "a damaged recording is taken");
    CHECK(ellicast_receiver_progress(r, &p) == ELLICAST_OK && p.objects == 1 && p.points_received > 0, "its intact packets");
    ellicast_receiver_destroy(r);
    ellicast_buffer_free(&stream);
}

/* A textured glTF from ../shared/samples, encoded from memory. */
static void check_gltf_in_memory(void) {
    char path[4096], glb_path[4096];
    unsigned char* bytes;
    size_t size = 0, i, with_uv = 0;
    ellicast_buffer stream = {NULL, 0}, glb = {NULL, 0};
    ellicast_receiver* r = NULL;
    ellicast_snapshot* s = NULL;
    ellicast_progress p;
    ellicast_mesh m;

    snprintf(path, sizeof path, "%s/gltf/Duck-glb/Duck.glb", samples_dir);
    if (!file_exists(path)) {
        printf("skipped: %s is absent (the tests read real assets from ../shared/samples)\n", path);
        return;
    }
    bytes = read_whole(path, &size);
    CHECK(bytes != NULL, "read %s", path);
    if (!bytes) return;
    CHECK(ellicast_encode_memory(bytes, size, "GLB", NULL, &stream) == ELLICAST_OK && stream.size > 1000, "encode the Duck from memory");
    free(bytes);
    CHECK(ellicast_receiver_create(NULL, &r) == ELLICAST_OK && ellicast_receiver_take_recording(r, stream.data, stream.size) == ELLICAST_OK,
          "receive it");
    CHECK(ellicast_receiver_progress(r, &p) == ELLICAST_OK && p.complete && p.exact_objects == p.objects && p.objects >= 1, "complete");
    CHECK(ellicast_receiver_snapshot(r, &s) == ELLICAST_OK, "snapshot");
    if (s) {
        for (i = 0; i < ellicast_snapshot_mesh_count(s); ++i)
            if (ellicast_snapshot_mesh(s, i, &m) == ELLICAST_OK && m.texcoords && m.normals) ++with_uv;
        CHECK(with_uv >= 1, "texture coordinates and normals come back");
        CHECK(ellicast_snapshot_glb(s, &glb) == ELLICAST_OK, "GLB");
        snprintf(glb_path, sizeof glb_path, "%s/duck.glb", scratch_dir);
        CHECK(glb.data && write_whole(glb_path, glb.data, glb.size), "write %s", glb_path);
        CHECK(validate_glb(glb_path) != 0, "the Duck's GLB is valid glTF");
        ellicast_buffer_free(&glb);
        ellicast_snapshot_destroy(s);
    }
    ellicast_receiver_destroy(r);
    ellicast_buffer_free(&stream);
}

int main(int argc, char** argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: test_capi SOURCE_DIR SHARED_SAMPLES_DIR SCRATCH_DIR\n");
        return 2;
    }
    source_dir = argv[1];
    samples_dir = getenv("ELLICAST_SHARED_SAMPLES") && *getenv("ELLICAST_SHARED_SAMPLES") ? getenv("ELLICAST_SHARED_SAMPLES") : argv[2];
    scratch_dir = argv[3];
    mkdir(scratch_dir, 0755);
    check_versions();
    check_bad_calls();
    check_round_trip();
    check_gltf_in_memory();
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}

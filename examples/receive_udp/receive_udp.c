/* receive_udp: a tiny ellicast receiver built only on the installed C API (ellicast.h).
 *
 *   receive_udp ADDRESS PORT OUT.glb [EVERY_SECONDS] [UNTIL_SECONDS]
 *
 * Listens for an ellicast broadcast on ADDRESS:PORT (IPv4 or IPv6, unicast or multicast: a
 * multicast ADDRESS is joined), gives every datagram to a receiver, and every EVERY_SECONDS
 * (default 2) writes what can be shown so far to OUT.glb (through OUT.glb.partial and a rename, so
 * a viewer never reads half a file). Stops when the stream is complete (every point, the exact
 * layer, the whole scene) or after UNTIL_SECONDS (default: no limit; Ctrl-C also stops), writing a
 * last snapshot. Progress goes to stderr. Exit status 0 when a GLB was written, 1 otherwise.
 *
 * Send something to it with the command-line tool, e.g.
 *   ellicast encode model.glb -o model.ellc
 *   ellicast serve model.ellc --to 127.0.0.1:5000 --rate 2000000
 *   receive_udp 127.0.0.1 5000 received.glb */
#define _DEFAULT_SOURCE /* struct ip_mreq, IN_MULTICAST */
#define _POSIX_C_SOURCE 200809L
#include <ellicast.h>

#include <arpa/inet.h>
#include <errno.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

static volatile sig_atomic_t stop;
static void on_signal(int sig) {
    (void)sig;
    stop = 1;
}

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* A UDP socket bound to ADDRESS:PORT; a multicast ADDRESS is joined on the default interface. */
static int open_socket(const char* address, const char* port) {
    struct addrinfo hints, *info = NULL;
    int fd, yes = 1, rc;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_DGRAM;
    hints.ai_flags = AI_NUMERICHOST | AI_PASSIVE;
    if ((rc = getaddrinfo(address, port, &hints, &info)) != 0) {
        fprintf(stderr, "receive_udp: %s:%s: %s\n", address, port, gai_strerror(rc));
        return -1;
    }
    fd = socket(info->ai_family, SOCK_DGRAM, 0);
    if (fd < 0) {
        perror("receive_udp: socket");
        freeaddrinfo(info);
        return -1;
    }
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    if (bind(fd, info->ai_addr, info->ai_addrlen) != 0) {
        fprintf(stderr, "receive_udp: cannot listen on %s:%s: %s\n", address, port, strerror(errno));
        close(fd);
        freeaddrinfo(info);
        return -1;
    }
    if (info->ai_family == AF_INET) {
        const struct sockaddr_in* a = (const struct sockaddr_in*)info->ai_addr;
        if (IN_MULTICAST(ntohl(a->sin_addr.s_addr))) {
            struct ip_mreq group;
            group.imr_multiaddr = a->sin_addr;
            group.imr_interface.s_addr = htonl(INADDR_ANY);
            if (setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &group, sizeof group) != 0)
                fprintf(stderr, "receive_udp: warning: cannot join %s: %s\n", address, strerror(errno));
        }
    } else if (info->ai_family == AF_INET6) {
        const struct sockaddr_in6* a = (const struct sockaddr_in6*)info->ai_addr;
        if (IN6_IS_ADDR_MULTICAST(&a->sin6_addr)) {
            struct ipv6_mreq group;
            group.ipv6mr_multiaddr = a->sin6_addr;
            group.ipv6mr_interface = 0;
            if (setsockopt(fd, IPPROTO_IPV6, IPV6_JOIN_GROUP, &group, sizeof group) != 0)
                fprintf(stderr, "receive_udp: warning: cannot join %s: %s\n", address, strerror(errno));
        }
    }
    freeaddrinfo(info);
    return fd;
}

/* Writes the receiver's current snapshot to `path` (through a temporary name). 1 when written. */
static int write_snapshot(ellicast_receiver* receiver, const char* path) {
    ellicast_buffer glb = {NULL, 0};
    char temporary[4096];
    FILE* f;
    int ok;
    ellicast_status status = ellicast_receiver_snapshot_glb(receiver, &glb);
    if (status == ELLICAST_ERROR_NOT_READY) return 0;
    if (status != ELLICAST_OK) {
        fprintf(stderr, "receive_udp: snapshot: %s\n", ellicast_last_error());
        return 0;
    }
    snprintf(temporary, sizeof temporary, "%s.partial", path);
    f = fopen(temporary, "wb");
    ok = f && fwrite(glb.data, 1, glb.size, f) == glb.size;
    if (f && fclose(f) != 0) ok = 0;
    if (ok && rename(temporary, path) != 0) ok = 0;
    if (!ok) {
        fprintf(stderr, "receive_udp: cannot write %s: %s\n", path, strerror(errno));
        remove(temporary);
    }
    ellicast_buffer_free(&glb);
    return ok;
}

static void report(const ellicast_receiver* receiver, double seconds) {
    ellicast_progress p;
    if (ellicast_receiver_progress(receiver, &p) != ELLICAST_OK) return;
    fprintf(stderr, "\r%6.1f s  datagrams %llu (new %llu, repeats %llu, dropped %llu)  loss %4.1f%%  points %llu/%llu  exact %u/%u%s",
            seconds, (unsigned long long)p.datagrams, (unsigned long long)p.accepted, (unsigned long long)p.duplicates,
            (unsigned long long)p.rejected, 100.0 * p.loss, (unsigned long long)p.points_received,
            (unsigned long long)p.points_declared, p.exact_objects, p.objects, p.complete ? "  complete" : "");
}

int main(int argc, char** argv) {
    static uint8_t datagram[65536];
    const char* output;
    double every = 2, until = -1, start, last_write;
    ellicast_receiver* receiver = NULL;
    ellicast_progress progress;
    int fd, written = 0;
    struct sigaction action;

    if (argc < 4 || argc > 6) {
        fprintf(stderr, "usage: receive_udp ADDRESS PORT OUT.glb [EVERY_SECONDS] [UNTIL_SECONDS]\n");
        return 2;
    }
    output = argv[3];
    if (argc > 4) every = atof(argv[4]);
    if (argc > 5) until = atof(argv[5]);
    if (!(every > 0) || (argc > 5 && !(until > 0))) {
        fprintf(stderr, "receive_udp: EVERY_SECONDS and UNTIL_SECONDS must be positive numbers\n");
        return 2;
    }
    fd = open_socket(argv[1], argv[2]);
    if (fd < 0) return 1;
    if (ellicast_receiver_create(NULL, &receiver) != ELLICAST_OK) {
        fprintf(stderr, "receive_udp: %s\n", ellicast_last_error());
        return 1;
    }
    memset(&action, 0, sizeof action);
    action.sa_handler = on_signal;
    sigaction(SIGINT, &action, NULL);
    sigaction(SIGTERM, &action, NULL);
    fprintf(stderr, "receive_udp: ellicast %s, listening on %s:%s\n", ellicast_version(), argv[1], argv[2]);

    start = last_write = now();
    while (!stop) {
        struct pollfd waiting;
        double t = now();
        waiting.fd = fd;
        waiting.events = POLLIN;
        if (until > 0 && t - start >= until) break;
        if (poll(&waiting, 1, 100) > 0) {
            /* Drain what is there: one datagram is one packet. */
            for (;;) {
                ssize_t n = recv(fd, datagram, sizeof datagram, MSG_DONTWAIT);
                if (n < 0) break;
                ellicast_receiver_take_datagram(receiver, datagram, (size_t)n); /* a dropped one is counted */
            }
        }
        t = now();
        if (t - last_write >= every) {
            written |= write_snapshot(receiver, output);
            last_write = t;
            report(receiver, t - start);
        }
        if (ellicast_receiver_progress(receiver, &progress) == ELLICAST_OK && progress.complete) break;
    }
    written |= write_snapshot(receiver, output);
    report(receiver, now() - start);
    fprintf(stderr, "\n");
    if (written) fprintf(stderr, "receive_udp: wrote %s\n", output);
    else fprintf(stderr, "receive_udp: nothing could be shown: no stream arrived\n");
    ellicast_receiver_destroy(receiver);
    close(fd);
    return written ? 0 : 1;
}

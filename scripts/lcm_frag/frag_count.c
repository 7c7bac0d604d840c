/* Counts the messages an LCM build delivers on one channel, for
 * scripts/lcm_frag.py: built once against Debian's liblcm and once against
 * the PyPI wheel's, it subscribes to CHANNEL on URL, prints "ready", and
 * prints one line per delivered message: its size and the first 4 bytes
 * (the sender's message number) until SECONDS of silence pass. */
#include <lcm/lcm.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/select.h>

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user) {
  (void)channel;
  (void)user;
  const uint8_t *d = (const uint8_t *)rbuf->data;
  uint32_t n = rbuf->data_size >= 4 ? ((uint32_t)d[0] << 24 | (uint32_t)d[1] << 16 | (uint32_t)d[2] << 8 | d[3]) : 0;
  printf("%u %u\n", (unsigned)rbuf->data_size, (unsigned)n);
  fflush(stdout);
}

int main(int argc, char **argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: frag_count URL CHANNEL SECONDS\n");
    return 2;
  }
  lcm_t *lcm = lcm_create(argv[1]);
  if (!lcm) return 1;
  lcm_subscribe(lcm, argv[2], on_message, NULL);
  printf("ready %d.%d.%d\n", LCM_MAJOR_VERSION, LCM_MINOR_VERSION, LCM_MICRO_VERSION);
  fflush(stdout);
  int fd = lcm_get_fileno(lcm);
  for (;;) {
    fd_set fds;
    FD_ZERO(&fds);
    FD_SET(fd, &fds);
    struct timeval tv = {atoi(argv[3]), 0};
    if (select(fd + 1, &fds, NULL, NULL, &tv) <= 0) break;
    lcm_handle(lcm);
  }
  lcm_destroy(lcm);
  return 0;
}

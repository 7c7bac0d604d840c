// Verifies that lcm-spy can decode every channel of a log with the jar of
// the generated message classes (tests/python/test_spy_jar.py runs it).
//
//   java -cp lcm.jar:contactsim_lcmtypes.jar:. DecodeLog LOG [CHANNEL_REGEX]
//
// Finds each event's class by its fingerprint in lcm-spy's own type database
// (which scans the class path, as lcm-spy does), decodes it and prints
// "CHANNEL CLASS COUNT" per channel; events on channels that do not match
// CHANNEL_REGEX (default: all) are skipped. Exit status 1 when an event has no
// class or does not decode.
import java.io.EOFException;
import java.io.IOException;
import java.util.Map;
import java.util.TreeMap;

import lcm.lcm.LCMDataInputStream;
import lcm.logging.Log;
import lcm.spy.LCMTypeDatabase;

public class DecodeLog {
  public static void main(String[] args) throws IOException {
    LCMTypeDatabase types = new LCMTypeDatabase();
    Log log = new Log(args[0], "r");
    String channels = args.length > 1 ? args[1] : ".*";
    Map<String, Integer> counts = new TreeMap<>();
    Map<String, String> classes = new TreeMap<>();
    int failures = 0;
    while (true) {
      Log.Event event;
      try {
        event = log.readNext();
      } catch (EOFException end) {
        break;
      }
      if (!event.channel.matches(channels)) continue;
      long fingerprint = new LCMDataInputStream(event.data).readLong();
      Class<?> cls = types.getClassByFingerprint(fingerprint);
      try {
        if (cls == null) throw new IllegalStateException("no class for fingerprint " + Long.toHexString(fingerprint));
        cls.getConstructor(byte[].class).newInstance((Object) event.data);
        classes.put(event.channel, cls.getName());
        counts.merge(event.channel, 1, Integer::sum);
      } catch (Exception e) {
        failures++;
        System.err.println(event.channel + ": " + e);
      }
    }
    for (Map.Entry<String, Integer> c : counts.entrySet())
      System.out.println(c.getKey() + " " + classes.get(c.getKey()) + " " + c.getValue());
    System.exit(failures == 0 ? 0 : 1);
  }
}

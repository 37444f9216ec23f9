// lagrange's Java SDK: a controller of your own in a lagrange run
// (controller.type: external). You write the law; run() keeps the contract of
// docs/external_programs.md -- the run's LCM URL, id, key and joint count
// from the environment, the MAC on every datagram (checked before anything is
// decoded), the header (run id, publisher, pid, per-channel seq, the run's
// clock, checksum), which positions to accept, lockstep's re-sent ticks
// (answered with the same command; the law is never stepped twice on one
// sample), the STATUS handshake, realtime. Shipped in
// build/share/java/lagrange_lcmtypes.jar beside the message classes.
//
//   System.exit(ExternalController.run((t, q) -> ExternalController.Command.of(u), null));
package lagrange.sdk;

import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.GeneralSecurityException;
import java.security.MessageDigest;
import java.util.Arrays;
import java.util.HashMap;
import java.util.HexFormat;
import java.util.Map;
import javax.crypto.Mac;
import javax.crypto.spec.SecretKeySpec;
import lagrange.channel_stats_t;
import lagrange.control_command_t;
import lagrange.header_t;
import lagrange.loop_stats_t;
import lagrange.plant_position_t;
import lagrange.status_t;
import lcm.lcm.LCM;
import lcm.lcm.LCMDataInputStream;
import lcm.lcm.LCMEncodable;
import lcm.lcm.LCMSubscriber;

public final class ExternalController implements LCMSubscriber {
  /** What the law returns for one sample: u [N m] and optional diagnostics (null: zeros). */
  public static final class Command {
    public double[] u, qDesired, qError, theta, filterState;

    public static Command of(double[] u) {
      Command c = new Command();
      c.u = u;
      return c;
    }
  }

  /** The law: the sample's sim time t [s] and joint angles q [rad] to the command. */
  public interface Step {
    Command step(double t, double[] q);
  }

  static final int MAC_BYTES = 32;
  static final int KEEP_ANSWERS = 64;  // lockstep re-sends only the tick it awaits

  private final Step law;
  private final Runnable reset;
  private final LCM lcm;
  private final long runId;
  private final int joints;
  private final Mac mac;
  private final long clockOffsetUs = clockOffset();
  private final int pid = (int) ProcessHandle.current().pid();
  private final Map<String, Long> seq = new HashMap<>();
  private final Map<Long, control_command_t> answered = new HashMap<>();
  private long lastTick = -1;
  private volatile boolean plantFinished = false;
  private volatile String error = null;

  private ExternalController(Step law, Runnable reset) throws IOException, GeneralSecurityException {
    this.law = law;
    this.reset = reset;
    this.runId = Long.parseLong(environment("LAGRANGE_RUN_ID"));
    this.joints = Integer.parseInt(environment("LAGRANGE_JOINTS"));
    String keyFile = environment("LAGRANGE_KEY_FILE");
    byte[] key;
    try {
      key = HexFormat.of().parseHex(Files.readString(Path.of(keyFile)).trim());
    } catch (IllegalArgumentException e) {
      key = new byte[0];
    }
    if (key.length != 32) throw new IllegalStateException("the run's key file " + keyFile + " does not hold 64 hex digits");
    mac = Mac.getInstance("HmacSHA256");
    mac.init(new SecretKeySpec(key, "HmacSHA256"));
    lcm = new LCM(environment("LAGRANGE_LCM_URL"));
    lcm.subscribe("PLANT_POSITION", this);
    lcm.subscribe("STATUS", this);
  }

  static String environment(String name) {
    String v = System.getenv(name);
    if (v == null || v.isEmpty())
      throw new IllegalStateException(name + " is not set: an external controller is started by `lagrange run` "
          + "(controller.type: external), which sets LAGRANGE_LCM_URL, LAGRANGE_RUN_ID, LAGRANGE_KEY_FILE, "
          + "LAGRANGE_JOINTS and LAGRANGE_MODE");
    return v;
  }

  // The run's clock: the monotonic one (System.nanoTime is CLOCK_MONOTONIC on
  // Linux) moved onto the wall clock by the offset every process of the run
  // stamps with (LAGRANGE_CLOCK_OFFSET_US), in µs.
  static long clockOffset() {
    String text = System.getenv("LAGRANGE_CLOCK_OFFSET_US");
    try {
      if (text != null) return Long.parseLong(text);
    } catch (NumberFormatException e) {
      // measured below
    }
    java.time.Instant now = java.time.Instant.now();
    return now.getEpochSecond() * 1_000_000L + now.getNano() / 1000 - System.nanoTime() / 1000;
  }

  // FNV-1a (64 bit) of the message encoded with checksum 0, never 0. Its
  // offset basis is lagrange's 1469598103934665603, not the standard one.
  static long checksum(LCMEncodable msg, header_t header) throws IOException {
    long kept = header.checksum;
    header.checksum = 0;
    ByteArrayOutputStream bytes = new ByteArrayOutputStream();
    msg.encode(new DataOutputStream(bytes));
    header.checksum = kept;
    long h = 1469598103934665603L;
    for (byte b : bytes.toByteArray()) h = (h ^ (b & 0xff)) * 0x100000001b3L;
    return h | 1L;
  }

  private header_t header(String channel, long tick, double simTime) {
    header_t h = new header_t();
    h.tick = Math.max(tick, 0);
    h.sim_time = simTime;
    h.publish_utime = System.nanoTime() / 1000 + clockOffsetUs;
    h.run_id = runId;
    h.publisher = "controller";
    h.publisher_pid = pid;
    long next = seq.getOrDefault(channel, 0L) + 1;
    seq.put(channel, next);
    h.seq = next;
    h.checksum = 0;
    return h;
  }

  private synchronized void publishSigned(String channel, LCMEncodable msg) throws IOException {
    ByteArrayOutputStream bytes = new ByteArrayOutputStream();
    msg.encode(new DataOutputStream(bytes));
    byte[] payload = bytes.toByteArray();
    byte[] tag = mac.doFinal(payload);
    byte[] datagram = Arrays.copyOf(payload, payload.length + MAC_BYTES);
    System.arraycopy(tag, 0, datagram, payload.length, MAC_BYTES);
    lcm.publish(channel, datagram, 0, datagram.length);
  }

  private synchronized byte[] authenticated(LCMDataInputStream ins) throws IOException {
    byte[] datagram = new byte[ins.available()];
    ins.readFully(datagram);
    if (datagram.length < MAC_BYTES) return null;
    byte[] payload = Arrays.copyOf(datagram, datagram.length - MAC_BYTES);
    byte[] tag = Arrays.copyOfRange(datagram, payload.length, datagram.length);
    return MessageDigest.isEqual(mac.doFinal(payload), tag) ? payload : null;  // constant time
  }

  private synchronized void publishCommand(control_command_t c) throws IOException {
    c.header = header("CONTROL_COMMAND", c.header.tick, c.header.sim_time);
    c.header.checksum = checksum(c, c.header);
    publishSigned("CONTROL_COMMAND", c);
  }

  private synchronized void publishStatus(String state) throws IOException {
    status_t s = new status_t();
    s.header = header("STATUS", lastTick, 0.0);
    s.process = "controller";
    s.state = state;
    s.last_tick = lastTick;
    s.tracking_error = Double.NaN;
    s.message = "";
    s.num_channels = 0;
    s.channels = new channel_stats_t[0];
    s.loop = new loop_stats_t();
    s.loop.scheduler = "";
    s.header.checksum = checksum(s, s.header);
    publishSigned("STATUS", s);
  }

  private double[] vector(double[] v, String what, plant_position_t p) {
    if (v == null && !what.equals("u")) return new double[joints];
    if (v == null || v.length != joints)
      throw new IllegalStateException("the law returned " + (v == null ? "no" : String.valueOf(v.length))
          + " numbers for " + what + "; expected " + joints + " (one per joint)");
    // NaN or infinity would leave here signed and valid, and stall the run at
    // the actuator (issue #46): refused at the source, naming the sample.
    for (int j = 0; j < joints; ++j)
      if (!Double.isFinite(v[j]))
        throw new IllegalStateException("the law returned " + v[j] + " for " + what + "[" + j + "] (joint "
            + (j + 1) + ") at the sample of tick " + p.header.tick + " (t = " + p.header.sim_time
            + " s); expected finite numbers");
    return v.clone();
  }

  private control_command_t command(plant_position_t p) {
    if (lastTick < 0 && reset != null) reset.run();
    Command out = law.step(p.header.sim_time, p.q.clone());
    control_command_t c = new control_command_t();
    c.header = new header_t();
    c.header.tick = p.header.tick;
    c.header.sim_time = p.header.sim_time;
    c.input_position_tick = p.header.tick;
    c.input_actuator_tick = -1;
    c.input_motor_tick = -1;
    c.num_joints = joints;
    c.u = vector(out.u, "u", p);
    c.q_desired = vector(out.qDesired, "q_desired", p);
    c.q_error = vector(out.qError, "q_error", p);
    c.theta = vector(out.theta, "theta", p);
    c.filter_state = vector(out.filterState, "filter_state", p);
    c.chain_order = 0;
    c.xi_error = new double[0][joints];
    return c;
  }

  @Override
  public synchronized void messageReceived(LCM lcm, String channel, LCMDataInputStream ins) {
    try {
      byte[] payload = authenticated(ins);
      if (payload == null || error != null) return;  // forged, altered, or not of this run: never decoded
      ins = new LCMDataInputStream(payload);
      if (channel.equals("STATUS")) {
        status_t s = new status_t(ins);
        if (s.header.run_id == runId && s.process.equals("plant") && s.state.equals("finished"))
          plantFinished = true;
        return;
      }
      plant_position_t p = new plant_position_t(ins);
      if (p.header.run_id != runId || !p.header.publisher.equals("plant") || checksum(p, p.header) != p.header.checksum
          || p.num_joints != joints)
        return;
      control_command_t cached = answered.get(p.header.tick);
      if (cached != null) {  // a re-sent position: the same answer again
        publishCommand(cached);
        return;
      }
      if (p.header.tick <= lastTick) return;  // older than one answered: never step back
      control_command_t c = command(p);
      answered.put(p.header.tick, c);
      final long oldest = p.header.tick - KEEP_ANSWERS;
      answered.keySet().removeIf(k -> k <= oldest);  // ticks skipped in realtime too
      lastTick = p.header.tick;
      publishCommand(c);
    } catch (IOException | RuntimeException e) {
      error = e.getMessage() == null ? e.toString() : e.getMessage();
    }
  }

  /**
   * Serves `law` as the run's controller until the plant finishes; calls `reset` (may be null) once
   * before the first sample. Returns 0 then; prints what broke the contract and returns 1 otherwise:
   * {@code System.exit(ExternalController.run(law, null));}
   */
  public static int run(Step law, Runnable reset) {
    try {
      ExternalController c = new ExternalController(law, reset);
      while (!c.plantFinished && c.error == null) {
        c.publishStatus(c.lastTick < 0 ? "ready" : "running");
        Thread.sleep(c.lastTick < 0 ? 100 : 500);
      }
      if (c.error != null) throw new IllegalStateException(c.error);
      for (int i = 0; i < 3; ++i) c.publishStatus("finished");
      c.lcm.close();
      return 0;
    } catch (Exception e) {
      System.err.println("controller: " + (e.getMessage() == null ? e.toString() : e.getMessage()));
      return 1;
    }
  }
}

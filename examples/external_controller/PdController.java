// A PD controller from outside the project: it takes the controller's place in
// a run (controller.type: external) through the LCM contract of
// docs/external_controllers.md, and nothing of lagrange is compiled into it
// but the message classes lcm-gen writes from lcmtypes/*.lcm.
//
//   u = -Kp (q - q_d) - Kd v,   v = (q_k - q_{k-1}) / (t_k - t_{k-1}) (0 at the first sample),
//
// with a constant q_d: no model, no gravity compensation -- for an arm
// without gravity (robot.gravity: 0) it regulates to q_d.
//
// Build and run (the test does this; lagrange builds the jar of message types):
//   javac -cp /usr/share/java/lcm.jar:build/share/java/lagrange_lcmtypes.jar -d /tmp/pd PdController.java
//   controller: {type: external, command: [java, -cp, "/tmp/pd:/usr/share/java/lcm.jar:...", PdController,
//                --kp, "20,5", --kd, "4,1", --qd, "0.5,-0.2"]}
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

public class PdController implements LCMSubscriber {
  private final LCM lcm;
  private final long runId;
  private final int joints;
  private final double[] kp, kd, qd;
  private final int pid = (int) ProcessHandle.current().pid();
  private final Map<String, Long> seq = new HashMap<>();  // per channel: the last sequence number sent
  private final Map<Long, control_command_t> answered = new HashMap<>();  // by tick
  private long lastTick = -1;
  private double[] previousQ;
  private double previousT;
  private volatile boolean plantFinished = false;
  private final Mac mac;  // HMAC-SHA256 with the run's key
  // publish_utime: the run's clock, the monotonic one (System.nanoTime is
  // CLOCK_MONOTONIC on Linux) moved onto the wall clock by the offset every
  // process of the run stamps with (LAGRANGE_CLOCK_OFFSET_US), in µs.
  private final long clockOffsetUs = clockOffset();

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

  static final int MAC_BYTES = 32;

  PdController(String url, long runId, byte[] key, int joints, double[] kp, double[] kd, double[] qd)
      throws IOException, GeneralSecurityException {
    this.mac = Mac.getInstance("HmacSHA256");
    this.mac.init(new SecretKeySpec(key, "HmacSHA256"));
    this.lcm = new LCM(url);
    this.runId = runId;
    this.joints = joints;
    this.kp = kp;
    this.kd = kd;
    this.qd = qd;
    lcm.subscribe("PLANT_POSITION", this);
    lcm.subscribe("STATUS", this);
  }

  // FNV-1a (64 bit) of the message encoded with checksum 0, never 0
  // (transport/checksum.hpp). Its offset basis is lagrange's 1469598103934665603,
  // not the standard 14695981039346656037 (docs/external_controllers.md).
  static long checksum(LCMEncodable msg) throws IOException {
    ByteArrayOutputStream bytes = new ByteArrayOutputStream();
    msg.encode(new DataOutputStream(bytes));
    long h = 1469598103934665603L;
    for (byte b : bytes.toByteArray()) h = (h ^ (b & 0xff)) * 0x100000001b3L;
    return h | 1L;
  }

  // The header every message carries: this run, publisher "controller", the
  // next sequence number of the channel; the checksum is set last (seal).
  header_t header(String channel, long tick, double simTime) {
    header_t h = new header_t();
    h.tick = tick;
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

  // Every datagram is the message's encoding followed by HMAC-SHA256 of that
  // encoding under the run's key (docs/external_controllers.md, "The MAC").
  synchronized void publishSigned(String channel, LCMEncodable msg) throws IOException {
    ByteArrayOutputStream bytes = new ByteArrayOutputStream();
    msg.encode(new DataOutputStream(bytes));
    byte[] payload = bytes.toByteArray();
    byte[] tag = mac.doFinal(payload);
    byte[] datagram = Arrays.copyOf(payload, payload.length + MAC_BYTES);
    System.arraycopy(tag, 0, datagram, payload.length, MAC_BYTES);
    lcm.publish(channel, datagram, 0, datagram.length);
  }

  // The payload of a datagram whose MAC is valid, or null: nothing else is decoded.
  synchronized byte[] authenticated(LCMDataInputStream ins) throws IOException {
    byte[] datagram = new byte[ins.available()];
    ins.readFully(datagram);
    if (datagram.length < MAC_BYTES) return null;
    byte[] payload = Arrays.copyOf(datagram, datagram.length - MAC_BYTES);
    byte[] tag = Arrays.copyOfRange(datagram, payload.length, datagram.length);
    return MessageDigest.isEqual(mac.doFinal(payload), tag) ? payload : null;  // constant time
  }

  synchronized void publishCommand(control_command_t c) throws IOException {
    c.header = header("CONTROL_COMMAND", c.header.tick, c.header.sim_time);
    c.header.checksum = checksum(c);
    publishSigned("CONTROL_COMMAND", c);
  }

  synchronized void publishStatus(String state) throws IOException {
    status_t s = new status_t();
    s.header = header("STATUS", Math.max(lastTick, 0), 0.0);  // a header tick is never negative
    s.process = "controller";
    s.state = state;
    s.last_tick = lastTick;
    s.tracking_error = Double.NaN;
    s.message = "";
    s.num_channels = 0;
    s.channels = new channel_stats_t[0];
    s.loop = new loop_stats_t();
    s.loop.scheduler = "";
    s.header.checksum = checksum(s);
    publishSigned("STATUS", s);
  }

  control_command_t command(plant_position_t p) {
    control_command_t c = new control_command_t();
    c.header = new header_t();
    c.header.tick = p.header.tick;
    c.header.sim_time = p.header.sim_time;
    c.input_position_tick = p.header.tick;
    c.input_actuator_tick = -1;
    c.input_motor_tick = -1;
    c.num_joints = joints;
    c.u = new double[joints];
    c.q_desired = qd.clone();
    c.q_error = new double[joints];
    c.theta = new double[joints];
    c.filter_state = new double[joints];
    c.chain_order = 0;
    c.xi_error = new double[0][joints];
    for (int j = 0; j < joints; ++j) {
      double v = previousQ == null ? 0.0 : (p.q[j] - previousQ[j]) / (p.header.sim_time - previousT);
      c.q_error[j] = p.q[j] - qd[j];
      c.theta[j] = v;
      c.u[j] = -kp[j] * c.q_error[j] - kd[j] * v;
    }
    previousQ = p.q.clone();
    previousT = p.header.sim_time;
    return c;
  }

  @Override
  public synchronized void messageReceived(LCM lcm, String channel, LCMDataInputStream ins) {
    try {
      byte[] payload = authenticated(ins);
      if (payload == null) return;  // forged, altered, or not of this run: never decoded
      ins = new LCMDataInputStream(payload);
      if (channel.equals("STATUS")) {
        status_t s = new status_t(ins);
        if (s.header.run_id == runId && s.process.equals("plant") && s.state.equals("finished"))
          plantFinished = true;
        return;
      }
      plant_position_t p = new plant_position_t(ins);
      // Only this run's plant, intact, with one angle per joint.
      long sent = p.header.checksum;
      p.header.checksum = 0;
      if (p.header.run_id != runId || !p.header.publisher.equals("plant") || checksum(p) != sent
          || p.num_joints != joints)
        return;
      p.header.checksum = sent;
      control_command_t cached = answered.get(p.header.tick);
      if (cached != null) {  // a re-sent position: the same answer again
        publishCommand(cached);
        return;
      }
      if (p.header.tick <= lastTick) return;  // older than one answered: never step back
      control_command_t c = command(p);
      answered.put(p.header.tick, c);
      answered.remove(p.header.tick - 64);
      lastTick = p.header.tick;
      publishCommand(c);
    } catch (IOException e) {
      System.err.println("PdController: " + channel + ": " + e);
    }
  }

  static double[] vector(String text, int joints) {
    String[] parts = text.split(",");
    double[] v = new double[joints];
    for (int j = 0; j < joints; ++j) v[j] = Double.parseDouble(parts[parts.length == 1 ? 0 : j]);
    return v;
  }

  public static void main(String[] args) throws Exception {
    int joints = Integer.parseInt(System.getenv("LAGRANGE_JOINTS"));
    Map<String, String> options = new HashMap<>();
    for (int i = 0; i + 1 < args.length; i += 2) options.put(args[i], args[i + 1]);
    // The run's key: 64 hex digits in a file only its owner reads.
    byte[] key = HexFormat.of().parseHex(Files.readString(Path.of(System.getenv("LAGRANGE_KEY_FILE"))).trim());
    PdController pd = new PdController(System.getenv("LAGRANGE_LCM_URL"),
        Long.parseLong(System.getenv("LAGRANGE_RUN_ID")), key, joints, vector(options.get("--kp"), joints),
        vector(options.get("--kd"), joints), vector(options.get("--qd"), joints));
    // STATUS twice a second (a realtime plant starts once it has heard
    // "ready"), until the plant says it has finished; then "finished" and out.
    while (!pd.plantFinished) {
      pd.publishStatus(pd.lastTick < 0 ? "ready" : "running");
      Thread.sleep(pd.lastTick < 0 ? 100 : 500);
    }
    for (int i = 0; i < 3; ++i) pd.publishStatus("finished");
    pd.lcm.close();
    System.exit(0);
  }
}

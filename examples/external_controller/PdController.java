// A PD controller from outside the project, in Java: the contract of
// docs/external_programs.md is kept by lagrange.sdk.ExternalController,
// shipped in the jar of this project's message types; this file is the law.
//
//   u = -Kp (q - q_d) - Kd v,   v = (q_k - q_{k-1}) / (t_k - t_{k-1}) (0 at the first sample),
//
// with a constant q_d: no model, no gravity compensation -- for an arm
// without gravity (robot.gravity: 0) it regulates to q_d.
//
// Build and run (the test does this; lagrange builds the jar):
//   javac -cp /usr/share/java/lcm.jar:build/share/java/lagrange_lcmtypes.jar -d /tmp/pd PdController.java
//   controller: {type: external, command: [java, -cp, "/tmp/pd:/usr/share/java/lcm.jar:...", PdController,
//                --kp, "20,5", --kd, "4,1", --qd, "0.5,-0.2"]}
import java.util.HashMap;
import java.util.Map;
import lagrange.sdk.ExternalController;

public class PdController {
  static double[] vector(String text, int joints) {
    String[] parts = text.split(",");
    double[] v = new double[joints];
    for (int j = 0; j < joints; ++j) v[j] = Double.parseDouble(parts[parts.length == 1 ? 0 : j]);
    return v;
  }

  public static void main(String[] args) {
    int joints = Integer.parseInt(System.getenv("LAGRANGE_JOINTS"));
    Map<String, String> options = new HashMap<>();
    for (int i = 0; i + 1 < args.length; i += 2) options.put(args[i], args[i + 1]);
    double[] kp = vector(options.get("--kp"), joints), kd = vector(options.get("--kd"), joints),
             qd = vector(options.get("--qd"), joints);
    double[][] previousQ = {null};
    double[] previousT = {0.0};
    System.exit(ExternalController.run((t, q) -> {
      ExternalController.Command c = new ExternalController.Command();
      c.u = new double[joints];
      c.qDesired = qd.clone();
      c.qError = new double[joints];
      c.theta = new double[joints];
      for (int j = 0; j < joints; ++j) {
        double v = previousQ[0] == null ? 0.0 : (q[j] - previousQ[0][j]) / (t - previousT[0]);
        c.qError[j] = q[j] - qd[j];
        c.theta[j] = v;
        c.u[j] = -kp[j] * c.qError[j] - kd[j] * v;
      }
      previousQ[0] = q;
      previousT[0] = t;
      return c;
    }, () -> previousQ[0] = null));
  }
}

// Decodes every hkf.head_pose_t on HEAD_POSE in an LCM log with the generated
// Java types (what lcm-spy relies on) and prints: count, first yaw, yaw sum.
import hkf.head_pose_t;
import java.io.EOFException;
import lcm.logging.Log;

public class DecodeHeadPoseLog {
    public static void main(String[] args) throws Exception {
        Log log = new Log(args[0], "r");
        int count = 0;
        double firstYaw = 0.0, yawSum = 0.0;
        while (true) {
            Log.Event event;
            try {
                event = log.readNext();
            } catch (EOFException end) {
                break;
            }
            if (!event.channel.equals("HEAD_POSE")) {
                continue;
            }
            head_pose_t pose = new head_pose_t(event.data);
            if (count == 0) {
                firstYaw = pose.yaw;
            }
            yawSum += pose.yaw;
            ++count;
        }
        log.close();
        System.out.printf(java.util.Locale.ROOT, "%d %.6f %.4f%n", count, firstYaw, yawSum);
    }
}

#pragma once

// What sounds the link-loss alarm: started when the alarm goes off, it
// repeats until stopped. ToneAlarmSound plays a tone on the sound card; tests
// pass a fake that records the calls.

class AlarmSound {
public:
    virtual ~AlarmSound() = default;
    virtual void start() = 0;  // repeating until stop(); idempotent
    virtual void stop() = 0;   // idempotent
};

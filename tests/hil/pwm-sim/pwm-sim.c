// SPDX-License-Identifier: GPL-2.0-only
/*
 * pwm-sim: a simulated PWM chip for tests.
 *
 * No kernel has a PWM simulator, so a PWM consumer could only be tested against a fake of the
 * sysfs files. This module registers a real pwm_chip with `npwm` channels (module parameter,
 * default 4) on a platform device named "pwm-sim". The PWM core therefore gives it the real
 * interface: /sys/class/pwm/pwmchipN/{export,unexport,npwm} and pwmK/{period,duty_cycle,
 * polarity,enable}, with the core's own validation. The chip's .apply accepts every state the
 * core passes on and records it, so a test can assert what the hardware would have been told:
 *
 *   /sys/kernel/debug/pwm-sim/state   one line per channel, the last applied state:
 *       pwm0 requested=1 enabled=1 period=1000000 duty_cycle=250000 polarity=normal applies=3
 *   /sys/kernel/debug/pwm-sim/log     every .apply call, oldest first, CLOCK_MONOTONIC time:
 *       123456789 pwm0 enabled=1 period=1000000 duty_cycle=250000 polarity=normal
 *     the newest `log_size` calls are kept (the first line says how many were dropped);
 *     writing anything to the file empties it.
 *
 * Part of vibscore's hardware-in-the-loop test tier (tests/hil), built out of tree against the
 * installed kernel's headers.
 */
#include <linux/debugfs.h>
#include <linux/err.h>
#include <linux/ktime.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/platform_device.h>
#include <linux/pwm.h>
#include <linux/seq_file.h>
#include <linux/slab.h>

static unsigned int npwm = 4;
module_param(npwm, uint, 0444);
MODULE_PARM_DESC(npwm, "number of PWM channels (1-64)");

static unsigned int log_size = 4096;
module_param(log_size, uint, 0444);
MODULE_PARM_DESC(log_size, "apply calls kept in the log (1-1048576)");

struct pwm_sim_entry {
	u64 time_ns;
	unsigned int channel;
	struct pwm_state state;
};

struct pwm_sim_channel {
	struct pwm_state state;
	bool requested;
	u64 applies;
};

struct pwm_sim {
	struct pwm_chip chip;
	struct platform_device *pdev;
	struct dentry *debugfs;
	struct mutex lock; /* guards channels and the log */
	struct pwm_sim_channel *channels;
	struct pwm_sim_entry *log; /* ring of log_size entries */
	unsigned int log_next;
	unsigned int log_count;
	u64 log_dropped;
};

static struct pwm_sim *sim;

static const char *polarity_name(enum pwm_polarity polarity)
{
	return polarity == PWM_POLARITY_INVERSED ? "inversed" : "normal";
}

static int pwm_sim_request(struct pwm_chip *chip, struct pwm_device *pwm)
{
	mutex_lock(&sim->lock);
	sim->channels[pwm->hwpwm].requested = true;
	mutex_unlock(&sim->lock);
	return 0;
}

static void pwm_sim_free(struct pwm_chip *chip, struct pwm_device *pwm)
{
	mutex_lock(&sim->lock);
	sim->channels[pwm->hwpwm].requested = false;
	mutex_unlock(&sim->lock);
}

static int pwm_sim_apply(struct pwm_chip *chip, struct pwm_device *pwm,
			 const struct pwm_state *state)
{
	struct pwm_sim_channel *channel = &sim->channels[pwm->hwpwm];
	struct pwm_sim_entry *entry;

	mutex_lock(&sim->lock);
	channel->state = *state;
	channel->applies++;
	entry = &sim->log[sim->log_next];
	entry->time_ns = ktime_get_ns();
	entry->channel = pwm->hwpwm;
	entry->state = *state;
	sim->log_next = (sim->log_next + 1) % log_size;
	if (sim->log_count < log_size)
		sim->log_count++;
	else
		sim->log_dropped++;
	mutex_unlock(&sim->lock);
	return 0;
}

static const struct pwm_ops pwm_sim_ops = {
	.request = pwm_sim_request,
	.free = pwm_sim_free,
	.apply = pwm_sim_apply,
	.owner = THIS_MODULE,
};

static int state_show(struct seq_file *out, void *unused)
{
	unsigned int i;

	mutex_lock(&sim->lock);
	for (i = 0; i < npwm; i++) {
		const struct pwm_sim_channel *channel = &sim->channels[i];

		seq_printf(out,
			   "pwm%u requested=%d enabled=%d period=%llu duty_cycle=%llu polarity=%s "
			   "applies=%llu\n",
			   i, channel->requested, channel->state.enabled, channel->state.period,
			   channel->state.duty_cycle, polarity_name(channel->state.polarity),
			   channel->applies);
	}
	mutex_unlock(&sim->lock);
	return 0;
}
DEFINE_SHOW_ATTRIBUTE(state);

static int log_show(struct seq_file *out, void *unused)
{
	unsigned int i, first;

	mutex_lock(&sim->lock);
	if (sim->log_dropped)
		seq_printf(out, "dropped %llu\n", sim->log_dropped);
	first = (sim->log_next + log_size - sim->log_count) % log_size;
	for (i = 0; i < sim->log_count; i++) {
		const struct pwm_sim_entry *entry = &sim->log[(first + i) % log_size];

		seq_printf(out, "%llu pwm%u enabled=%d period=%llu duty_cycle=%llu polarity=%s\n",
			   entry->time_ns, entry->channel, entry->state.enabled,
			   entry->state.period, entry->state.duty_cycle,
			   polarity_name(entry->state.polarity));
	}
	mutex_unlock(&sim->lock);
	return 0;
}

static int log_open(struct inode *inode, struct file *file)
{
	return single_open(file, log_show, inode->i_private);
}

static ssize_t log_write(struct file *file, const char __user *buffer, size_t count,
			 loff_t *position)
{
	mutex_lock(&sim->lock);
	sim->log_next = 0;
	sim->log_count = 0;
	sim->log_dropped = 0;
	mutex_unlock(&sim->lock);
	return count;
}

static const struct file_operations log_fops = {
	.owner = THIS_MODULE,
	.open = log_open,
	.read = seq_read,
	.llseek = seq_lseek,
	.release = single_release,
	.write = log_write,
};

static void pwm_sim_release(void)
{
	if (sim->pdev)
		platform_device_unregister(sim->pdev);
	kvfree(sim->log);
	kfree(sim->channels);
	kfree(sim);
	sim = NULL;
}

static int __init pwm_sim_init(void)
{
	int ret;

	if (npwm < 1 || npwm > 64 || log_size < 1 || log_size > 1048576)
		return -EINVAL;
	sim = kzalloc(sizeof(*sim), GFP_KERNEL);
	if (!sim)
		return -ENOMEM;
	mutex_init(&sim->lock);
	sim->channels = kcalloc(npwm, sizeof(*sim->channels), GFP_KERNEL);
	sim->log = kvcalloc(log_size, sizeof(*sim->log), GFP_KERNEL);
	sim->pdev = platform_device_register_simple("pwm-sim", PLATFORM_DEVID_NONE, NULL, 0);
	if (!sim->channels || !sim->log || IS_ERR(sim->pdev)) {
		ret = IS_ERR(sim->pdev) ? PTR_ERR(sim->pdev) : -ENOMEM;
		if (IS_ERR(sim->pdev))
			sim->pdev = NULL;
		pwm_sim_release();
		return ret;
	}

	sim->chip.dev = &sim->pdev->dev;
	sim->chip.ops = &pwm_sim_ops;
	sim->chip.base = -1;
	sim->chip.npwm = npwm;
	ret = pwmchip_add(&sim->chip);
	if (ret) {
		pwm_sim_release();
		return ret;
	}

	sim->debugfs = debugfs_create_dir("pwm-sim", NULL);
	debugfs_create_file("state", 0444, sim->debugfs, NULL, &state_fops);
	debugfs_create_file("log", 0644, sim->debugfs, NULL, &log_fops);
	return 0;
}

static void __exit pwm_sim_exit(void)
{
	debugfs_remove_recursive(sim->debugfs);
	pwmchip_remove(&sim->chip);
	pwm_sim_release();
}

module_init(pwm_sim_init);
module_exit(pwm_sim_exit);

MODULE_DESCRIPTION("Simulated PWM chip recording every applied state, for tests");
MODULE_LICENSE("GPL");
